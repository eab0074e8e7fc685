// The inside of a droplet (common/droplets.glsl), for both integrators: needs the program's map() and
// the marcher's castRay, which the droplets' own probes (dropletprobe.frag) do without.
//
// Inside droplet id, from ro along rd: the chord's length to its surface (tOut), and the scene's surface
// when it comes first, in a droplet the scene cuts (map() at its centre closer than its radius): true
// with h then. Both integrators walk the liquid by it (sdf_main.glsl's insideDroplet, the path
// tracer's throughLiquid); what a crossing costs of their budgets is each one's own.
bool liquidChord(int id, vec3 ro, vec3 rd, float side, float pathT, out float tOut, out Hit h)
{
    vec4 s = droplet(id);
    float t0;
    sphereRoots(ro, rd, s, t0, tOut);
    tOut = max(tOut, 0.0);
    h = Hit(false, 0.0, -1.0, 0, false, 0);
    if (map(s.xyz).x < s.w)
        h = castRay(ro, rd, tOut, side, pathT);
    return h.hit;
}
