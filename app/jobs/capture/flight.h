/* flight — a camera path (app/view/path.h) rendered frame by frame, headless: `fathom render --path F
 * --frames A-B --output out/frame_%04d.png`. Frame n shows the path at time first key + n / fps.
 * Each frame is an offline shot (verified, atomic write; its file remembers scene, overrides and
 * camera, so `--scene frame.png` renders it again). A frame whose file already exists is skipped, so
 * a run killed part way (a crash, a pre-empted farm job) resumes where it stopped, and several
 * processes can share one range. One GL context serves every frame. An output ending in .mp4, .webm or
 * .mkv is a video: the frames go to its folder and the video is made from them (jobs/capture/flight_video.h). */
#ifndef FATHOM_FLIGHT_H
#define FATHOM_FLIGHT_H

#include <stdbool.h>

#include "jobs/capture/offline.h"
#include "util.h"

/* What to fly: the path file, the scene and overrides every frame starts from, the frames (all of them
 * unless has_frames), the frame rate (0: 30) and the output pattern (one %d); each frame is `shot`'s
 * kind of offline shot (size, AOVs, bands, quiet), at spp samples (0: the scene's). */
typedef struct flight_desc {
    const char *path, *output, *scene;
    const char *video; /* a video output's --video options, or NULL (jobs/capture/flight_video.h) */
    const char *const *sets;
    int set_count, spp, fps;
    bool has_frames;
    int frame_first, frame_last;
    offline_desc shot;
} flight_desc;

bool flight_render(const flight_desc *d, err_t *err);

#endif
