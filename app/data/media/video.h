/* video — flights straight to video: frames (8-bit RGB, rows top first) encoded by libavcodec into an
 * MP4 (H.264 or AV1), WebM (VP9 or AV1) or Matroska file, and decoded back (the tests compare).
 * libavcodec and its encoders' libraries load only when a run first writes or reads a video: the
 * encoder lives in fathom_video.so (data/lazy/lazy.h), reached through video_lazy.c.
 *
 * Colour: the frames are sRGB; the video is YCbCr with BT.709's primaries and matrix, limited range, and
 * the frames' own sRGB transfer curve (IEC 61966-2-1, not BT.709's), each tagged so (players show the
 * frames' colours). A 360° flight (equirectangular) is tagged as spherical video and a stereo one
 * with its layout, where the container holds it (MP4: the sv3d and st3d boxes, Matroska/WebM:
 * projection and stereo mode), so VR players show it as one.
 *
 * Options (--video, comma-separated KEY=VALUE): codec=h264|av1|vp9 (default: h264 for .mp4 and .mkv,
 * vp9 for .webm), crf=N (constant quality: lower is better; 0-51 for h264, 0-63 else; defaults 12 for
 * h264, 3 for vp9, 1 for av1 (SVT-AV1 at preset 8): each keeps the worst frame of the csg flight at
 * 640x360 over 40.5 dB RGB PSNR, at 1 and 3 frames a second), pix_fmt=yuv420p|yuv444p
 * (default yuv420p: what every player plays; it needs an even width and height). */
#ifndef FATHOM_VIDEO_H
#define FATHOM_VIDEO_H

#include <stdbool.h>
#include <stdint.h>

#include "util.h"

enum { VIDEO_MAX_SIDE = 16384 }; /* a frame's width or height at most (fathom's largest image) */
typedef enum video_codec { VIDEO_H264, VIDEO_AV1, VIDEO_VP9, VIDEO_CODEC_COUNT } video_codec;
typedef struct video_options {
    video_codec codec;
    int crf;
    bool yuv444;
} video_options;
/* What a player should know of the picture: 360° equirectangular and the stereo layout (0 none, 1
 * side by side with the left eye left, 2 top-bottom with the left eye on top). */
typedef struct video_view {
    bool equirectangular;
    int stereo;
} video_view;

/* Whether path names a video fathom writes (.mp4, .webm, .mkv). */
bool video_is_file(const char *path);
/* The options for the video at path (text may be NULL: the defaults). */
bool video_options_parse(const char *text, const char *path, video_options *o, err_t *err);
/* The options as text video_options_parse reads back (for messages and the record). */
void video_options_describe(const video_options *o, char *out, size_t n);

typedef struct video_writer video_writer;
/* Starts a video at path (written as it goes: the caller writes to a temporary name and renames). */
video_writer *video_open(const char *path, int width, int height, int fps, const video_options *o,
                         const video_view *view, err_t *err);
bool video_frame(video_writer *v, const uint8_t *rgb, err_t *err);
/* Flushes the encoder and closes the file; frees v either way. */
bool video_finish(video_writer *v, err_t *err);
void video_abort(video_writer *v);

/* A video read back: its size, frame count and rate, codec, tags and (when rgb is not NULL) every
 * frame as 8-bit RGB, rows top first, one after another (malloc'd). */
typedef struct video_info {
    int width, height, frames;
    double fps;
    char codec[32];
    video_view view;
} video_info;
bool video_decode(const char *path, video_info *info, uint8_t **rgb, err_t *err);

#endif
