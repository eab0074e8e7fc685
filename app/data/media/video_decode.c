/* video_decode — a video read back (data/media/video.h's video_decode): in fathom_video.so with video.c. */
#include "data/media/video.h"

#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/spherical.h>
#include <libavutil/stereo3d.h>
#include <libswscale/swscale.h>
#include <stdlib.h>
#include <string.h>

typedef struct reader {
    AVFormatContext *fc;
    AVCodecContext *c;
    struct SwsContext *sws;
    AVFrame *frame;
    AVPacket *pkt;
    int stream;
    video_info *info;
    uint8_t **rgb;
    size_t cap;
} reader;

static void tags(const AVStream *st, video_view *view)
{
    size_t size;
    const uint8_t *sp = av_stream_get_side_data(st, AV_PKT_DATA_SPHERICAL, &size);
    view->equirectangular = sp && ((const AVSphericalMapping *)sp)->projection == AV_SPHERICAL_EQUIRECTANGULAR;
    const uint8_t *s3 = av_stream_get_side_data(st, AV_PKT_DATA_STEREO3D, &size);
    view->stereo = !s3 ? 0 : ((const AVStereo3D *)s3)->type == AV_STEREO3D_SIDEBYSIDE ? 1
                 : ((const AVStereo3D *)s3)->type == AV_STEREO3D_TOPBOTTOM ? 2 : 0;
}

/* The decoded frame appended as RGB (BT.709 limited range in, as video.c wrote it). */
static bool keep(reader *r, err_t *err)
{
    video_info *in = r->info;
    in->frames++;
    if (!r->rgb)
        return true;
    size_t one = (size_t)3 * (size_t)in->width * (size_t)in->height;
    if ((size_t)in->frames * one > r->cap) {
        size_t cap = r->cap ? 2 * r->cap : 8 * one;
        uint8_t *p = realloc(*r->rgb, cap);
        if (!p)
            return err_set(err, "out of memory for the video's frames");
        *r->rgb = p;
        r->cap = cap;
    }
    if (!r->sws) {
        r->sws = sws_getContext(in->width, in->height, (enum AVPixelFormat)r->frame->format, in->width, in->height,
                                AV_PIX_FMT_RGB24, SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, NULL, NULL, NULL);
        if (!r->sws)
            return err_set(err, "no conversion to RGB");
        const int *bt709 = sws_getCoefficients(SWS_CS_ITU709);
        sws_setColorspaceDetails(r->sws, bt709, 0, bt709, 1, 0, 1 << 16, 1 << 16);
    }
    uint8_t *dst[1] = {*r->rgb + (size_t)(in->frames - 1) * one};
    int stride[1] = {3 * in->width};
    sws_scale(r->sws, (const uint8_t *const *)r->frame->data, r->frame->linesize, 0, in->height, dst, stride);
    return true;
}

static bool drain(reader *r, const AVPacket *pkt, err_t *err)
{
    int e = avcodec_send_packet(r->c, pkt);
    if (e < 0 && e != AVERROR_EOF)
        return err_set(err, "the video does not decode");
    while ((e = avcodec_receive_frame(r->c, r->frame)) >= 0)
        if (!keep(r, err))
            return false;
    return e == AVERROR(EAGAIN) || e == AVERROR_EOF || err_set(err, "the video does not decode");
}

static bool open_reader(reader *r, const char *path, err_t *err)
{
    if (avformat_open_input(&r->fc, path, NULL, NULL) < 0 || avformat_find_stream_info(r->fc, NULL) < 0)
        return err_set(err, "%s: not a video fathom can read", path);
    const AVCodec *codec = NULL;
    r->stream = av_find_best_stream(r->fc, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
    if (r->stream < 0 || !codec)
        return err_set(err, "%s: no video stream this machine decodes", path);
    const AVStream *st = r->fc->streams[r->stream];
    r->c = avcodec_alloc_context3(codec);
    r->frame = av_frame_alloc();
    r->pkt = av_packet_alloc();
    if (!r->c || !r->frame || !r->pkt || avcodec_parameters_to_context(r->c, st->codecpar) < 0 ||
        avcodec_open2(r->c, codec, NULL) < 0)
        return err_set(err, "%s: its decoder does not open", path);
    video_info *in = r->info;
    in->width = r->c->width;
    in->height = r->c->height;
    in->fps = av_q2d(st->avg_frame_rate);
    snprintf(in->codec, sizeof in->codec, "%s", avcodec_get_name(st->codecpar->codec_id));
    tags(st, &in->view);
    return true;
}

bool video_decode(const char *path, video_info *info, uint8_t **rgb, err_t *err)
{
    *info = (video_info){0};
    if (rgb)
        *rgb = NULL;
    av_log_set_level(AV_LOG_FATAL);
    reader r = {.info = info, .rgb = rgb};
    bool ok = open_reader(&r, path, err);
    while (ok && av_read_frame(r.fc, r.pkt) >= 0) {
        if (r.pkt->stream_index == r.stream)
            ok = drain(&r, r.pkt, err);
        av_packet_unref(r.pkt);
    }
    ok = ok && drain(&r, NULL, err);
    sws_freeContext(r.sws);
    av_frame_free(&r.frame);
    av_packet_free(&r.pkt);
    avcodec_free_context(&r.c);
    avformat_close_input(&r.fc);
    if (!ok && rgb) {
        free(*rgb);
        *rgb = NULL;
    }
    return ok;
}
