/* aov — the layout of the per-pixel outputs besides colour (render_read_aovs): AOV_FLOATS floats a
 * pixel, rows top first. Depth is the distance along the unit ray to the first hit, +inf on a miss;
 * steps counts the primary ray's march steps (height samples on terrain), negated when the ray was
 * left unresolved (its budget and the tail after it ran out: common/march.glsl; drawn as a miss), and
 * negated with half a step more, −(steps + ½), when the pixel ran out of the loop budget or the driver
 * cut its loops (common/budget.glsl; drawn as a miss too);
 * exit is the direction in which the main path left the scene; variance is, per colour channel, the
 * variance of the pixel's mean over its samples (the sample variance / n: the square of its standard
 * error; −1 where the pixel took one sample and nothing is known); samples is n; position is the
 * first hit's world position (computed from depth and the pixel's ray, in double); albedo the first
 * hit's material colour. */
#ifndef FATHOM_AOV_H
#define FATHOM_AOV_H

enum {
    AOV_FLOATS = 18,
    AOV_SLOT_NORMAL = 0, /* x, y, z */
    AOV_SLOT_DEPTH = 3,
    AOV_SLOT_STEPS = 4,
    AOV_SLOT_EXIT = 5, /* x, y, z */
    AOV_SLOT_VARIANCE = 8, /* r, g, b */
    AOV_SLOT_SAMPLES = 11,
    AOV_SLOT_POSITION = 12, /* x, y, z: the world point the depth reaches along the pixel's ray (centre of
                               the lens or eye: camera_ray_from), 0 on a miss */
    AOV_SLOT_ALBEDO = 15, /* r, g, b: the first hit's material colour (textures included), 0 on a miss */
};

#endif
