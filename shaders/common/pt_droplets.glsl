// A path through droplets (common/pathtrace.glsl, common/droplets.glsl): their surfaces reflect or
// refract with the exact Fresnel split, Beer–Lambert inside; they spend DROPLET_EVENTS, not bounces.
#if FX_DROPLETS
// A droplet's surface at p (outward normal nOut) from the air (entering) or the liquid: the path
// reflects or refracts by the exact Fresnel split, drawn at random.
void dropletSurface(inout Walk W, int id, vec3 p, vec3 nOut, bool entering)
{
    W.dropEvents++;
    W.dir = dirAfterDelta(W.dir); // as glass
    vec3 n = entering ? nOut : -nOut;        // faces the coming ray
    float eta = entering ? 1.0 / uDropletIor : uDropletIor;
    if (rand01(W.rng) < fresnelDielectric(max(-dot(W.rd, n), 0.0), eta)) {
        turn(W, p, reflect(W.rd, n), vec3(0.0));
        W.dropSkip = entering ? id : -1;
    } else {
        turn(W, p, refract(W.rd, n, eta), vec3(0.0));
        W.dropIn = entering ? id : -1;
        W.dropSkip = entering ? -1 : id;
    }
}

// Inside droplet W.dropIn: Beer over the chord to its surface, then its surface; true (with h) when
// the scene's surface comes first (a droplet the scene cuts: the path leaves the liquid there).
bool throughLiquid(inout Walk W, out Hit h)
{
    vec4 s = droplet(W.dropIn);
    float tOut;
    liquidChord(W.dropIn, W.ro, W.rd, W.side, W.pathT, tOut, h);
    W.throughput *= exp(-uDropletAbsorption * (h.hit ? h.t : tOut));
    if (h.hit) {
        W.dropIn = -1;
        return true;
    }
    vec3 p = W.ro + W.rd * tOut;
    W.pathT += tOut;
    int next = dropletAt(p, W.dropIn);
    if (next >= 0) { // overlapping droplets are one body of liquid: no surface here
        W.dropEvents++;
        W.dropIn = next;
        turn(W, p, W.rd, vec3(0.0));
        return false;
    }
    dropletSurface(W, W.dropIn, p, normalize(p - s.xyz), false);
    return false;
}

// The nearest droplet the air segment meets before `end` (its surface, or the march's end): its
// number and distance, or −1; droplets below the level of detail on the way dim the path.
int dropletAhead(inout Walk W, float end, out float tDrop)
{
    tDrop = 1e30;
    if (W.dropIn >= 0 || W.dropEvents >= DROPLET_EVENTS || !fxOn(FX_DROPLETS_BIT))
        return -1;
    vec3 reflected = vec3(0.0);
    int cells;
    int id = dropletsWalk(W.ro, W.rd, 0.0, DROPLET_CULL != 0 ? end : float(MAX_DIST) - W.pathT, end, W.dropSkip,
                          W.pathT, W.throughput, reflected, tDrop, cells);
    W.radiance += reflected * environmentBlurred(W.rd, 1.0);
    W.dropSkip = -1;
    if (id < 0 || tDrop >= end)
        tDrop = 1e30;
    return tDrop < 1e30 ? id : -1;
}
#endif
