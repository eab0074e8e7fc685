// The terrain program: a heightfield under the contract in app/data/geo/terrain.h (texel centres on a regular
// grid, bilinear between them, Y up, metres). Primary rays use either
//  - the max-mipmap traversal (TERRAIN_MAXMIP; Tevs, Ihrke, Seidel 2008): descend a pyramid of cell
//    maxima, skipping every node the ray passes above, and intersect the bilinear patch of each cell
//    it reaches exactly (a quadratic along the ray). Exact: no ray tunnels through a ridge.
//  - the height-field lab's search: enter the slab [hmin, hmax], step linearly with steps growing by
//    STEP_GROWTH, and refine the first bracketed crossing by BINARY_STEPS bisections. A step can jump
//    over a ridge thinner than itself (tests/geo/test_terrain.c shows where).
// Hit.steps counts height samples (texel fetches of four corners count once) for --aov steps.
// The grid in tiles (app/data/geo/terrain_tiles.h, app/gpu/res_heightfield.c): a tile holds 2^shift cells and
// their corners (its last column and row are its neighbours' first), R32F metres, in the texture layer
// the page table names (−1: not resident, streamed from disk). Texel (i, j) = column i (west → east), row
// j (north → south).
uniform sampler2DArray uHeight;
// The max pyramid: level 0 (cells between four centres) is not stored (the walk intersects a cell
// instead); levels 1 … uTerrainTileLevel − 1 per tile (mip k − 1 = level k), the levels from whole tiles
// up (uTerrainTileLevel …) in uHeightMaxTop.
uniform sampler2DArray uHeightMax;
uniform sampler2D uHeightMaxTop;
uniform isampler2D uTerrainPages; // tile → its layer, −1 when not resident
uniform ivec2 uTerrainTiles;
uniform ivec2 uTerrainTileShift; // log2 of cells a tile
uniform int uTerrainTileLevel;
uniform vec2 uTerrainOrigin;     // x0, z0: the north-west corner of the grid
uniform vec2 uTerrainSpacing;    // dx, dz: metres per texel
uniform float uTerrainHeightMin, uTerrainHeightMax; // metres (also read by terrain/layers.glsl)
uniform float uTerrainStepScale; // 1 / sqrt(1 + L²), L the steepest slope: (y − h) · this bounds the distance
uniform int uTerrainTopLevel;    // the max pyramid's top level
uniform ivec2 uTerrainSize;      // texels
uniform int uTerrainMaxNodes;    // the max-mipmap traversal's node budget: enough for any ray across the grid

#if TERRAIN_STREAM
// A streamed terrain's feedback, one bit a tile: words [0, n) the tiles asked for and not resident,
// [n, 2n) the resident tiles used. res_heightfield_settle reads it, loads what was asked and draws again.
uniform int uTerrainFeedbackWords;
layout(std430) buffer TerrainFeedback { uint uTerrainFeedback[]; };
int gTerrainLastTile = -1; // this invocation's last tile: marked once a run of lookups
#endif

// The layer holding tile `tile`, −1 when it is not resident.
int terrainSlot(ivec2 tile)
{
    tile = clamp(tile, ivec2(0), uTerrainTiles - 1);
    int slot = texelFetch(uTerrainPages, tile, 0).r;
#if TERRAIN_STREAM
    int idx = tile.y * uTerrainTiles.x + tile.x;
    if (idx != gTerrainLastTile) {
        gTerrainLastTile = idx;
        atomicOr(uTerrainFeedback[(idx >> 5) + (slot < 0 ? 0 : uTerrainFeedbackWords)], 1u << uint(idx & 31));
    }
#endif
    return slot;
}

// A tile's highest cell (the top pyramid's node at the tile level): what a missing tile stands as.
float terrainTileMax(ivec2 tile) { return texelFetch(uHeightMaxTop, tile, 0).r; }

#include "common/hit.glsl"
#include "common/uniforms.glsl" // fxOn (each file is included once a program)

#define PROGRAM_CAST_RAY 1
#define PROGRAM_NORMAL 1
#define PROGRAM_NORMAL_OUTWARD 1 // a heightfield is hit from outside: shading normals are bent, not flipped
#define PROGRAM_ALBEDO 1

// Cell space: c = (xz − x0z0) / dxdz − ½ puts texel centres on integers; cell (i, j) is [i, i+1]×[j, j+1].
vec2 toCell(vec2 xz) { return (xz - uTerrainOrigin) / uTerrainSpacing - 0.5; }

// The Earth's curvature (terrain.curvature, TERRAIN_CURVATURE): the ground d metres from the camera lies lower
// by (1 − k) d² / 2R (R 6,371 km, k 0.13: refraction bends the sight lines, the surveyors' coefficient and
// the viewshed's rule, data/geo/viewshed.h), times the exaggeration. Worked as the ray rising instead: its
// effective height y + c |xz − camera|² is a quadratic in t, and so is its clearance over a bilinear cell, so
// the walk and each cell's intersection stay exact. curvedY: a point's height above the curved ground's
// datum (its altitude, what the layers, water and shadows compare with the DEM's heights).
#if TERRAIN_CURVATURE
uniform float uCurvature; // c = exaggeration (1 − k) / 2R, per world unit
float curveDrop(vec2 xz) { vec2 d = xz - uCamPos.xz; return uCurvature * dot(d, d); }
#else
float curveDrop(vec2 xz) { return 0.0; }
#endif
float curvedY(vec3 p) { return p.y + curveDrop(p.xz); }
// The ray's effective height at t: e.x + e.y t + e.z t².
vec3 rayCurve(vec3 ro, vec3 rd)
{
#if TERRAIN_CURVATURE
    vec2 u = ro.xz - uCamPos.xz;
    return vec3(ro.y + uCurvature * dot(u, u), rd.y + 2.0 * uCurvature * dot(u, rd.xz), uCurvature * dot(rd.xz, rd.xz));
#else
    return vec3(ro.y, rd.y, 0.0);
#endif
}
float curveAt(vec3 e, float t) { return e.x + (e.y + e.z * t) * t; }
// The roots lo ≤ hi of A t² + B t + C (A ≠ 0), without cancellation; false when there are none.
bool quadRoots(float A, float B, float C, out float lo, out float hi)
{
    float disc = B * B - 4.0 * A * C;
    lo = hi = -1.0;
    if (disc < 0.0)
        return false;
    float q = -0.5 * (B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
    float r1 = q / A, r2 = q != 0.0 ? C / q : r1;
    lo = min(r1, r2), hi = max(r1, r2);
    return true;
}
// The smallest root in (0, ∞) of A t² + B t + C (C > 0: the ray starts above), −1 if none.
float firstRoot(float A, float B, float C)
{
    if (abs(A) < 1e-30)
        return B < 0.0 ? -C / B : -1.0;
    float lo, hi;
    if (!quadRoots(A, B, C, lo, hi))
        return -1.0;
    return lo > 0.0 ? lo : hi > 0.0 ? hi : -1.0;
}

// The heights at cell `cell`'s corners (h00, h10, h01, h11), from the tile holding the cell; a tile not
// resident stands as a plateau at its maximum (conservative: never below the ground it holds). A cell
// beyond the grid has no surface (holes).
vec4 cellCorners(ivec2 cell)
{
    if (any(lessThan(cell, ivec2(0))) || any(greaterThan(cell, uTerrainSize - 2)))
        return vec4(-1e30);
    ivec2 tile = cell >> uTerrainTileShift;
    int slot = terrainSlot(tile);
    if (slot < 0)
        return vec4(terrainTileMax(tile));
    ivec2 p = cell - (tile << uTerrainTileShift);
    return vec4(texelFetch(uHeight, ivec3(p, slot), 0).r, texelFetch(uHeight, ivec3(p + ivec2(1, 0), slot), 0).r,
                texelFetch(uHeight, ivec3(p + ivec2(0, 1), slot), 0).r, texelFetch(uHeight, ivec3(p + ivec2(1, 1), slot), 0).r);
}

// The maximum of pyramid node `node` at `level` (≥ 1).
float nodeMax(ivec2 node, int level)
{
    if (level >= uTerrainTileLevel)
        return texelFetch(uHeightMaxTop, node, level - uTerrainTileLevel).r;
    ivec2 shift = max(uTerrainTileShift - level, 0); // log2 of this level's nodes per tile
    ivec2 tile = node >> shift;
    int slot = terrainSlot(tile);
    if (slot < 0)
        return terrainTileMax(tile);
    return texelFetch(uHeightMax, ivec3(node - (tile << shift), slot), level - 1).r;
}
// Nodata texels hold −1e30 (app/data/geo/terrain.h TERRAIN_HOLE): a cell with one at a corner has no surface,
// and a height interpolated with any weight on one is far below every real height.
bool isHole(float h) { return h < -1e20; }
bool cellSolid(ivec2 cell)
{
    if (any(lessThan(cell, ivec2(0))) || any(greaterThan(cell, uTerrainSize - 2)))
        return false;
    vec4 h = cellCorners(cell);
    return !isHole(min(min(h.x, h.y), min(h.z, h.w)));
}

// The bilinear patch with corners k (h00, h10, h01, h11) at f in the cell.
float bilinear(vec4 k, vec2 f) { return mix(mix(k.x, k.y, f.x), mix(k.z, k.w, f.x), f.y); }

float heightAtCell(vec2 c)
{
    c = clamp(c, vec2(0.0), vec2(uTerrainSize - 1));
    ivec2 i = min(ivec2(floor(c)), uTerrainSize - 2);
    vec2 f = c - vec2(i);
    vec4 k = cellCorners(i);
    if (isHole(min(min(k.x, k.y), min(k.z, k.w))))
        return -1e30; // no surface in a cell with a nodata corner, even on its edges
    return bilinear(k, f);
}

float terrainHeight(vec2 xz) { return heightAtCell(toCell(xz)); }

// A distance bound for shadows and AO: vertical clearance shrunk by the steepest slope.
vec2 map(vec3 p) { return vec2((curvedY(p) - terrainHeight(p.xz)) * uTerrainStepScale, 0.0); }

// Where the ray is over the footprint and inside the slab [hmin, hmax]: (t enter, t exit).
vec2 terrainSlab(vec3 ro, vec3 rd)
{
    // For rays going down, the slab reaches a little below hmin: ground lying exactly at the minimum
    // (a sea clamped flat) is then met inside the slab, not at its exit, where float rounding decided
    // hit or miss. Rays from below still enter the column through its floor at hmin.
    float below = rd.y < 0.0 ? 1e-4 * (uTerrainHeightMax - uTerrainHeightMin) + 1e-3 : 0.0;
    vec3 lo = vec3(uTerrainOrigin.x + 0.5 * uTerrainSpacing.x, uTerrainHeightMin - below,
                   uTerrainOrigin.y + 0.5 * uTerrainSpacing.y);
    vec3 hi = vec3(uTerrainOrigin.x + (float(uTerrainSize.x) - 0.5) * uTerrainSpacing.x, uTerrainHeightMax,
                   uTerrainOrigin.y + (float(uTerrainSize.y) - 0.5) * uTerrainSpacing.y);
    vec3 inv = 1.0 / rd; // ±inf for an axis the ray does not move along: the slab test still works
    vec3 t0 = (lo - ro) * inv, t1 = (hi - ro) * inv;
    vec3 tmin = min(t0, t1), tmax = max(t0, t1);
    // a zero direction component gives NaN when ro sits exactly on that plane: treat as inside
    tmin = mix(tmin, vec3(-1e30), isnan(tmin));
    tmax = mix(tmax, vec3(1e30), isnan(tmax));
#if TERRAIN_CURVATURE // the ray's effective height rises: it is under hmax between the roots of e(t) = hmax
    vec3 e = rayCurve(ro, rd);
    if (!quadRoots(e.z, e.y, e.x - uTerrainHeightMax, tmin.y, tmax.y))
        return vec2(1.0, 0.0); // (no floor: a curved ground has none to meet from below)
#endif
    float enter = max(max(max(tmin.x, tmin.y), tmin.z), 0.0);
    // The terrain is solid from hmin up to the ground: a ray that comes in through a side wall in the
    // sliver below hmin is under the floor and stays there (it goes down): it misses. Before, it hit
    // the wall 1–2 mm below the floor, a strip along a DEM's bottom edge.
#if !TERRAIN_CURVATURE
    if (rd.y < 0.0 && enter > 0.0 && ro.y + rd.y * enter < uTerrainHeightMin)
        return vec2(1.0, 0.0);
#endif
    return vec2(enter, min(min(tmax.x, tmax.y), tmax.z));
}

// First s in [0, sEnd] where the ray meets the bilinear patch with corner heights k (h00, h10, h01, h11)
// coming from above (0 when it is at or below the patch already); from below (the ray under the patch,
// a terrain's water seen from inside it) where it rises through it. −1 if none. uv: the ray's position in
// the cell at s = 0, cd its cell-space velocity, y0 and dy its height and climb.
float patchRoot(vec4 k, vec2 uv, vec2 cd, float y0, float dy, float ddy, float sEnd, bool fromBelow)
{
    float h00 = k.x, h10 = k.y, h01 = k.z, h11 = k.w;
    float a = h10 - h00, b = h01 - h00, c = h00 - h10 - h01 + h11;
    // y(s) − h(s) = A s² + B s + C (its negative from below: the same roots, C > 0 on the ray's side)
    float A = ddy - c * cd.x * cd.y; // ddy: the ray's own curve (the Earth's: rayCurve)
    float B = dy - (a * cd.x + b * cd.y + c * (uv.x * cd.y + uv.y * cd.x));
    float C = y0 - (h00 + a * uv.x + b * uv.y + c * uv.x * uv.y);
    if (fromBelow)
        A = -A, B = -B, C = -C;
    if (C <= 0.0)
        return 0.0; // already at or past the surface where the ray enters the cell
    float s = -1.0;
    if (abs(A) < 1e-12 * max(abs(B), 1e-30)) {
        s = B < 0.0 ? -C / B : -1.0;
    } else {
        float disc = B * B - 4.0 * A * C;
        if (disc >= 0.0) {
            float q = -0.5 * (B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc)); // no cancellation
            float r1 = q / A, r2 = q != 0.0 ? C / q : -1.0;
            float lo = min(r1, r2), hi = max(r1, r2);
            s = lo >= 0.0 ? lo : hi;
        }
    }
    return (s >= 0.0 && s <= sEnd) ? s : -1.0;
}

// First s in [0, sEnd] where the ray meets cell `cell`'s bilinear patch; −1 if none. c0: the ray's
// cell-space position at s = 0, cd its cell-space velocity, y0 and dy its height and climb.
float intersectCell(ivec2 cell, vec2 c0, vec2 cd, float y0, float dy, float ddy, float sEnd)
{
    vec4 k = cellCorners(cell);
    if (isHole(min(min(k.x, k.y), min(k.z, k.w))))
        return -1.0; // a nodata hole: rays pass (the max pyramid skips it; the linear search comes here)
    return patchRoot(k, c0 - vec2(cell), cd, y0, dy, ddy, sEnd, false);
}

#if FX_WATER && TERRAIN_WATER_GRID
// Water a texel at a time (terrain.water "fill" or a raster: app/gpu/res_heightfield.c): each texel's water
// level, −1e30 where dry; the max pyramid holds max(ground, water), so no ray skips a lake. A cell with a wet
// corner holds the bilinear patch of its corners' levels, a dry corner taking the wet ones' mean (a lake's
// cell: flat at its level), and there is water where that patch lies above the ground: the shoreline is
// where the two patches cross, found exactly as the nearer root of the two.
uniform sampler2D uWaterGrid;

bool cellWater(ivec2 cell, out vec4 k)
{
    k = vec4(-1e30);
    if (any(lessThan(cell, ivec2(0))) || any(greaterThan(cell, uTerrainSize - 2)))
        return false;
    k = vec4(texelFetch(uWaterGrid, cell, 0).r, texelFetch(uWaterGrid, cell + ivec2(1, 0), 0).r,
             texelFetch(uWaterGrid, cell + ivec2(0, 1), 0).r, texelFetch(uWaterGrid, cell + ivec2(1, 1), 0).r);
    vec4 wet = vec4(greaterThan(k, vec4(-1e20)));
    float n = dot(wet, vec4(1.0));
    if (n == 0.0)
        return false;
    float mean = dot(k * wet, vec4(1.0)) / n;
    k = mix(vec4(mean), k, wet);
    return true;
}

// The water's level at cell coordinates c; −1e30 where there is none.
float waterAtCell(vec2 c)
{
    vec4 k;
    ivec2 i = clamp(ivec2(floor(c)), ivec2(0), uTerrainSize - 2);
    if (!cellWater(i, k))
        return -1e30;
    return bilinear(k, clamp(c - vec2(i), 0.0, 1.0));
}

// Where the ray meets cell `cell`'s water in [0, sEnd], from above or from below; −1 if it does not.
float waterCell(ivec2 cell, vec2 c0, vec2 cd, float y0, float dy, float ddy, float sEnd)
{
    vec4 k;
    if (!cellWater(cell, k))
        return -1.0;
    vec2 uv = c0 - vec2(cell);
    return patchRoot(k, uv, cd, y0, dy, ddy, sEnd, y0 < bilinear(k, uv));
}
#endif

#if TERRAIN_MAXMIP
// water: meet a terrain's water drawn a texel at a time too (the primary and bounce rays; not shadow rays)
Hit terrainTrace(vec3 ro, vec3 rd, vec2 slab, bool water)
{
    Hit h = Hit(false, slab.y, 0.0, 0, false, 0);
    vec2 c0 = toCell(ro.xz), cd = rd.xz / uTerrainSpacing;
    vec2 dirSign = vec2(cd.x >= 0.0 ? 1.0 : -1.0, cd.y >= 0.0 ? 1.0 : -1.0);
    const float NUDGE = 1e-4; // cells: moves a point on a node boundary into the node ahead
    int top = uTerrainTopLevel, level = top;
    float t = slab.x;
    vec3 e = rayCurve(ro, rd); // the ray's effective height (the Earth's curvature: a quadratic)
    for (int i = 0; i < uTerrainMaxNodes; i++) { // exact: its budget follows the grid, not a quality knob
        vec2 c = c0 + cd * t;
        float size = float(1 << level);
        // the nudge must exceed the rounding of c, recomputed from an origin far away: relative to |c0|
        vec2 nudge = max(vec2(NUDGE), 8.0 * PRECISION_REL * (abs(c0) + abs(cd * t)));
        ivec2 node = ivec2(floor((c + dirSign * nudge * vec2(notEqual(cd, vec2(0.0)))) / size));
        vec2 far = (vec2(node) + max(dirSign, 0.0)) * size;
        vec2 tAxis = mix((far - c0) / cd, vec2(1e30), equal(cd, vec2(0.0)));
        float tExit = min(min(tAxis.x, tAxis.y), slab.y);
        h.steps++;
        if (level == 0) {
            float y = curveAt(e, t), dy = e.y + 2.0 * e.z * t;
            float s = intersectCell(node, c0 + cd * t, cd, y, dy, e.z, tExit - t);
#if FX_WATER && TERRAIN_WATER_GRID
            float sw = water ? waterCell(node, c0 + cd * t, cd, y, dy, e.z, tExit - t) : -1.0;
            if (sw >= 0.0 && (s < 0.0 || sw < s)) {
                h.hit = true;
                h.t = t + sw;
                h.mat = float(uWaterMaterial);
                return h;
            }
#endif
            if (s >= 0.0) {
                h.hit = true;
                h.t = t + s;
                return h;
            }
        } else {
            float ymin = min(curveAt(e, t), curveAt(e, tExit)), tv = e.z > 0.0 ? -e.y / (2.0 * e.z) : -1.0;
            if (tv > t && tv < tExit) // the curve's lowest point inside the node
                ymin = min(ymin, curveAt(e, tv));
            if (ymin <= nodeMax(node, level)) {
                level--; // the ray may meet something in here: look closer
                continue;
            }
        }
        t = tExit; // nothing in this node: past it, and back up a level
        if (t >= slab.y)
            break;
        level = min(level + 1, top);
    }
    h.t = slab.y;
    return h;
}
#else
float hsSurfaceY(vec2 xz) { return terrainHeight(xz) - curveDrop(xz); } // the ground as the flat frame sees it
#include "common/heightsearch.glsl"

Hit terrainTrace(vec3 ro, vec3 rd, vec2 slab, bool water) // (water a texel at a time needs maxmip: scene_terrain.c)
{
    Hit h = Hit(false, slab.y, 0.0, 0, false, 0);
    float texel = min(uTerrainSpacing.x, uTerrainSpacing.y);
    float along = max(length(rd.xz), 1e-3); // horizontal metres per metre of ray
    float dt = min(float(LINEAR_STEP) * texel / along, (uTerrainHeightMax - uTerrainHeightMin) + texel);
    float t = heightSearch(ro, rd, slab.x, slab.y, dt, h.steps);
    if (t >= 0.0) {
        h.hit = true;
        h.t = t;
    }
    return h;
}
#endif

#if FX_WATER
// Water (terrain.water) as a level over the DEM, wherever the ground lies below it: its surface is the plane
// y = uWaterLevel over the cells that have a surface; the ray meets the nearer of it and the ground, both
// exact, so the shoreline is where the plane cuts each bilinear patch, at every zoom. (As lakes or a raster,
// TERRAIN_WATER_GRID: the walk meets it, above.) Its look is a material's (uWaterMaterial: glass,
// common/sdf_main.glsl and common/pathtrace.glsl).
#define WATER_EVENTS 4 // water surfaces a path crosses or reflects at without spending a bounce: in, out, TIR

#if TERRAIN_WATER_GRID
float waterLevelAt(vec2 c) { return waterAtCell(c); }
#else
uniform float uWaterLevel; // world height (the level times the exaggeration)
float waterLevelAt(vec2 c) { return uWaterLevel; }
#endif

// Water at p: over the grid, below the water's surface, above ground that has a surface (so not over a hole).
bool waterAt(vec3 p)
{
    vec2 c = toCell(p.xz);
    float y = curvedY(p);
    if (any(lessThan(c, vec2(0.0))) || any(greaterThan(c, vec2(uTerrainSize - 1))) || y >= waterLevelAt(c))
        return false;
    float g = heightAtCell(c);
    return !isHole(g) && g < y;
}

// The water's surface normal at p (outward: up).
vec3 waterNormal(vec3 p)
{
    vec2 g = vec2(0.0);
#if TERRAIN_WATER_GRID
    vec2 c = toCell(p.xz), e = vec2(0.25, 0.0); // the patch's slope: a flood's surface tilts, a lake's is level
    if (!isHole(min(min(waterLevelAt(c + e.xy), waterLevelAt(c - e.xy)), min(waterLevelAt(c + e.yx), waterLevelAt(c - e.yx)))))
        g = vec2(waterLevelAt(c + e.xy) - waterLevelAt(c - e.xy), waterLevelAt(c + e.yx) - waterLevelAt(c - e.yx)) /
            (2.0 * e.x * uTerrainSpacing);
#endif
#if TERRAIN_CURVATURE // a level on a curved Earth curves with it
    g -= 2.0 * uCurvature * (p.xz - uCamPos.xz);
#endif
    return normalize(vec3(-g.x, 1.0, -g.y));
}

// Where the ray crosses the level's plane in (0, tEnd), −1 if it does not: from above or from below.
float waterCross(vec3 ro, vec3 rd, float tEnd)
{
#if TERRAIN_WATER_GRID
    return -1.0; // the walk meets it
#else
    vec3 e = rayCurve(ro, rd); // the level is the curved ground's: e(t) = level
    float t = (uWaterLevel - ro.y) / rd.y; // ±inf or NaN for a level ray: no crossing
    if (e.z > 0.0) // from above, or from below where the rising curve meets the level
        t = e.x >= uWaterLevel ? firstRoot(e.z, e.y, e.x - uWaterLevel) : firstRoot(-e.z, -e.y, uWaterLevel - e.x);
    if (!(t > 0.0 && t < tEnd))
        return -1.0;
    // the crossing is on the surface by construction: only whether water lies there (over the grid, above
    // ground that has a surface) is asked; its height recomputed from t and the drop rounds either way
    vec2 c = toCell(ro.xz + rd.xz * t);
    if (any(lessThan(c, vec2(0.0))) || any(greaterThan(c, vec2(uTerrainSize - 1))))
        return -1.0;
    float g = heightAtCell(c);
    return !isHole(g) && g < uWaterLevel ? t : -1.0;
#endif
}

// A camera under the water's surface starts in it: its material, −1 elsewhere (common/sdf_main.glsl).
#define PROGRAM_START_INSIDE 1
int programStartInside(vec3 p) { return fxOn(FX_WATER_BIT) && waterAt(p) ? uWaterMaterial : -1; }
#endif

Hit castRay(vec3 ro, vec3 rd, float tmax, float side, float pathT)
{
    vec2 slab = terrainSlab(ro, rd);
    slab.y = min(slab.y, tmax);
    Hit h = Hit(false, tmax, 0.0, 1, false, 0);
    if (slab.x <= slab.y)
        h = terrainTrace(ro, rd, slab, fxOn(FX_WATER_BIT));
    if (!h.hit)
        h.t = tmax;
#if FX_WATER
    float tw = fxOn(FX_WATER_BIT) ? waterCross(ro, rd, h.t) : -1.0;
    if (tw >= 0.0)
        h = Hit(true, tw, float(uWaterMaterial), h.steps + 1, false, 0);
#endif
    return h;
}

// Shadows with the terrain's own marcher: a hard shadow is a castRay hit; a soft one steps toward the
// light with the lab's growing steps and takes the penumbra from the least clearance over distance,
// k · (y − h) / t (the heightfield form of Quilez's estimate). Both stop once the ray is above hmax.
#define PROGRAM_SHADOWS 1
float hardShadow(vec3 ro, vec3 rd, float tmax, float pathT)
{
    vec2 slab = terrainSlab(ro, rd);
    slab.y = min(slab.y, tmax);
    return slab.x <= slab.y && terrainTrace(ro, rd, slab, false).hit ? 0.0 : 1.0;
}

float softShadow(vec3 ro, vec3 rd, float tmax, float k, float pathT)
{
    vec2 slab = terrainSlab(ro, rd);
    slab.y = min(slab.y, tmax);
    float res = 1.0, t = slab.x;
    float dt = float(LINEAR_STEP) * min(uTerrainSpacing.x, uTerrainSpacing.y) / max(length(rd.xz), 1e-3);
    for (int i = 0; i < SHADOW_STEPS && t < slab.y; i++) {
        vec3 p = ro + rd * t;
        float clearance = curvedY(p) - terrainHeight(p.xz);
        if (clearance <= 0.0)
            return 0.0;
        res = min(res, k * clearance / max(t, 1e-6));
        t += dt;
        dt *= float(STEP_GROWTH);
    }
    res = clamp(res, 0.0, 1.0);
    return res * res * (3.0 - 2.0 * res);
}

// The normal of the surface the ray hit. On the wall of the terrain's column (a ray that reached the
// footprint's edge, or a nodata hole's, below the surface) the wall's: the nearest cell face, facing
// the side without a surface; on its floor (hmin, met from below) straight down. On the surface, with TERRAIN_PATCH_NORMALS the hit bilinear patch's
// exact normal; otherwise (the default, a documented choice) a smooth normal, the heightfield's
// central differences one texel either side, which hides the patches' creases at the cost of
// disagreeing with the patch by up to ~10° on sharp ridges. A smooth normal that would look across a
// hole falls back to the patch's.
vec3 patchNormal(vec2 c)
{
    ivec2 i = clamp(ivec2(floor(c)), ivec2(0), uTerrainSize - 2);
    vec2 f = clamp(c - vec2(i), 0.0, 1.0);
    vec4 q = cellCorners(i);
    float h00 = q.x, h10 = q.y, h01 = q.z, h11 = q.w;
    float a = h10 - h00, b = h01 - h00, k = h00 - h10 - h01 + h11;
    vec2 g = vec2(a + k * f.y, b + k * f.x) / uTerrainSpacing; // dh/dx, dh/dz in metres per metre
#if TERRAIN_CURVATURE // the curved ground's own slope: the drop's gradient, 2c (xz − camera)
    g -= 2.0 * uCurvature * ((c + 0.5) * uTerrainSpacing + uTerrainOrigin - uCamPos.xz);
#endif
    return normalize(vec3(-g.x, 1.0, -g.y));
}

vec3 calcNormal(vec3 p, float eps, vec3 fallback)
{
    float dx = uTerrainSpacing.x, dz = uTerrainSpacing.y;
    vec2 c = toCell(p.xz);
    float y = curvedY(p);
    if (y < terrainHeight(p.xz) - eps || !cellSolid(clamp(ivec2(floor(c)), ivec2(0), uTerrainSize - 2))) {
        if (y < uTerrainHeightMin + eps) // the column's floor, met from below
            return vec3(0, -1, 0);
        vec2 r = round(c), d = abs(c - r) * uTerrainSpacing;
        if (d.x < d.y) // an x face: the normal points to the cell on its side without a surface
            return cellSolid(ivec2(int(r.x) - 1, int(floor(c.y)))) ? vec3(1, 0, 0) : vec3(-1, 0, 0);
        return cellSolid(ivec2(int(floor(c.x)), int(r.y) - 1)) ? vec3(0, 0, 1) : vec3(0, 0, -1);
    }
#if TERRAIN_PATCH_NORMALS
    return patchNormal(c);
#else
    float xp = terrainHeight(p.xz + vec2(dx, 0.0)), xm = terrainHeight(p.xz - vec2(dx, 0.0));
    float zp = terrainHeight(p.xz + vec2(0.0, dz)), zm = terrainHeight(p.xz - vec2(0.0, dz));
    if (isHole(min(min(xp, xm), min(zp, zm))))
        return patchNormal(c);
    vec2 g = vec2((xp - xm) / (2.0 * dx), (zp - zm) / (2.0 * dz));
#if TERRAIN_CURVATURE // the curved ground's own slope (central differences of a quadratic: exact)
    g -= 2.0 * uCurvature * (p.xz - uCamPos.xz);
#endif
    return normalize(vec3(-g.x, 1.0, -g.y));
#endif
}

// Materials by slope and altitude: sand low, snow high and flat, grass on gentle slopes, rock on
// the rest (triplanar texturing keeps cliffs unstretched): terrain/layers.glsl, which needs the
// material uniforms, so both come here.
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base);
#include "common/uniforms.glsl"
#include "common/material.glsl"
#define TERRAIN_ALTITUDE(p) curvedY(p) // the layers' heights: above the curved ground's datum
#include "terrain/layers.glsl"

#if FX_WATER
// Light reaching p under the water (common/lights.glsl: through the surface above p, then down to p): the
// water's depth over p, its index and absorption; false where p is not under the water.
#define PROGRAM_LIGHT_MEDIUM 1
bool programLightMedium(vec3 p, out float depth, out float ior, out vec3 sigma)
{
    depth = 0.0, ior = 1.0, sigma = vec3(0.0);
    vec2 c = toCell(p.xz);
    if (!fxOn(FX_WATER_BIT) || any(lessThan(c, vec2(0.0))) || any(greaterThan(c, vec2(uTerrainSize - 1))))
        return false;
    float level = waterLevelAt(c);
    depth = level - curvedY(p);
    ior = max(uMatIor[uWaterMaterial], 1.0);
    sigma = uMatAbsorption[uWaterMaterial];
    return depth > 0.0 && !isHole(level);
}
#endif
