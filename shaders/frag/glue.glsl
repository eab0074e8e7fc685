// A Fragmentarium fragment as a formula (app/scene/formula/frag.h, app/scene/scene_programs.c includes this
// after the fragment's translation): its DE() is the estimate, init() runs once per pixel, and the
// surface is coloured as DE renderers colour it from orbitTrap. The fragment's DE is marched as it
// is, with no bounding sphere (FORMULA_EXACT): fragments declare none.

#ifndef FRAG_COLOR_HOOK // DE-Raytracer 0.9.1 named it color() (frag/raytracer_v091.frag)
#define FRAG_COLOR_HOOK baseColor
#endif

bool fragInitDone = false;
void fragInit()
{
    if (!fragInitDone) {
#ifdef FRAG_VERTEX_INIT // what a #vertex section computed once a vertex (app/scene/formula/frag_vertex.c)
        fragVertexInit();
#endif
#ifdef providesInit
        init();
#endif
        fragInitDone = true;
    }
}

real formulaDE(real3 p, out float trap)
{
    fragInit();
    orbitTrap = vec4(10000.0);
    trap = 0.0;
    return real(DE(vec3(p)));
}

// A cosine palette about the trap value s: each channel's phase is the colour's component.
vec3 fragCycle(vec3 c, float s) { return 0.5 + 0.5 * cos(s * Cycles + c); }

// The renderers' colouring: each trap component (the radius as √r²) weights its colour by its
// strength (w); the sum, tripled, replaces BaseColor by OrbitStrength. providesColor: the fragment's
// baseColor() replaces the sum. Colours are display values (as the host showed them).
vec3 fragSurface(vec3 p, vec3 n)
{
#ifdef providesColor
    return mix(BaseColor, FRAG_COLOR_HOOK(p, n), OrbitStrength);
#else
    vec4 t = vec4(orbitTrap.xyz, sqrt(max(orbitTrap.w, 0.0)));
    vec3 sum = CycleColors ? fragCycle(X.xyz, t.x) * X.w * t.x + fragCycle(Y.xyz, t.y) * Y.w * t.y +
                                 fragCycle(Z.xyz, t.z) * Z.w * t.z + fragCycle(R.xyz, t.w) * R.w * t.w
                           : X.xyz * X.w * t.x + Y.xyz * Y.w * t.y + Z.xyz * Z.w * t.z + R.xyz * R.w * t.w;
    return mix(BaseColor, 3.0 * sum, OrbitStrength);
#endif
}

// fathom's look: the colour decoded to linear albedo as sRGB-ish display values
vec3 fragColor(vec3 p, vec3 n) { return pow(clamp(fragSurface(p, n), 0.0, 1.0), vec3(2.2)); }

#define FORMULA_ALBEDO 1
#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    fragInit();
    orbitTrap = vec4(10000.0);
    loopSpend(uFormulaLoops);
    vec3 w = vec3(worldOf(p));
    DE(w);
    return fragColor(w, n);
}

// 3D.frag's values of this pixel (frag/raytracer.frag) from its primary ray (common/sdf_main.glsl)
void fragHost(vec3 ro, vec3 rd)
{
    from = ro;
    dir = rd;
    Dir = uCamForward;
    UpOrtho = uCamUp;
    Right = uCamRight;
    coord = vec2(dot(rd, uCamRight), dot(rd, uCamUp)) / max(dot(rd, uCamForward), 1e-6);
    viewCoord = coord / uTanHalfFov * vec2(uResolution.y / uResolution.x, 1.0);
    pixelSize = 1.0 / uResolution;
}
#define PROGRAM_PIXEL_START fragHost

// What the fragment's own look (frag/look.glsl, after the fragment's names are gone again) takes from it:
// its estimate with a fresh orbit trap, the trap's colour, and its background hook.
float fragDE(vec3 p) { return DE(p); }
void fragTrapReset() { orbitTrap = vec4(10000.0); }
#ifdef providesBackground
#define FRAG_BACKGROUND 1
vec3 fragBackgroundHook(vec3 dir) { return backgroundColor(dir); }
#endif
