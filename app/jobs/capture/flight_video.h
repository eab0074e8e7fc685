/* flight_video — a flight straight to a video (`render --path F --output flight.mp4`): the frames are
 * rendered as PNGs into flight.mp4.frames/ (so a killed render resumes, and several processes can
 * share the range; a folder fathom did not make is refused, and a frame counts only if the folder's
 * manifest holds its digest), then the video is encoded from the frames on disk (data/media/video.h), written to a
 * temporary file, synced and renamed: a video that is there is whole. */
#ifndef FATHOM_FLIGHT_VIDEO_H
#define FATHOM_FLIGHT_VIDEO_H

#include <stdbool.h>
#include <stddef.h>

#include "data/media/video.h"
#include "util.h"

/* The frames' pattern for the video at output ("OUTPUT.frames/%05d.png"), its folder made, and the
 * options (--video's text, or NULL) parsed. */
bool flight_video_prepare(const char *output, const char *options, char *pattern, size_t n, video_options *o,
                          err_t *err);
/* The frames' manifest (in the frames' folder): frame f at name is the one fathom wrote, or record it. */
#define FRAMES_MANIFEST "fathom-frames.txt"
bool flight_video_frame_trusted(const char *pattern, int f, const char *name);
bool flight_video_frame_record(const char *pattern, int f, const char *name, err_t *err);
/* The video from frames 0 … last of pattern at fps, when every one of them is there; else a note on
 * what is missing (a farm's chunk: the last run assembles it) and true. */
bool flight_video_assemble(const char *output, const char *pattern, int last, int fps, const video_options *o,
                           const video_view *view, bool quiet, err_t *err);

#endif
