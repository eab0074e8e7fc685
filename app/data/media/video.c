/* video — the libavcodec side (data/media/video.h): built into fathom_video.so, loaded on first use. */
#include "data/media/video.h"

#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libavutil/pixdesc.h>
#include <libavutil/spherical.h>
#include <libavutil/stereo3d.h>
#include <libswscale/swscale.h>
#include <stdlib.h>
#include <string.h>

struct video_writer {
    AVFormatContext *fc;
    AVCodecContext *c;
    AVStream *st;
    struct SwsContext *sws;
    AVFrame *frame;
    AVPacket *pkt;
    int64_t pts;
    bool header;
};

static bool av_fail(err_t *err, const char *what, int code)
{
    char msg[AV_ERROR_MAX_STRING_SIZE] = "";
    av_strerror(code, msg, sizeof msg);
    return err_set(err, "%s: %s", what, msg);
}

/* The encoders for each codec, the first this machine has wins. */
static const char *const ENCODERS[VIDEO_CODEC_COUNT][3] = {
    [VIDEO_H264] = {"libx264", NULL},
    [VIDEO_AV1] = {"libsvtav1", "libaom-av1", NULL},
    [VIDEO_VP9] = {"libvpx-vp9", NULL},
};

/* The container by the file's extension (video_is_file's). */
static const char *container(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && !strcmp(dot, ".webm") ? "webm" : dot && !strcmp(dot, ".mkv") ? "matroska" : "mp4";
}

/* Tags a player reads: 360° and the stereo layout (stream side data the muxers write). */
static bool tag_view(AVStream *st, const video_view *view)
{
    if (view->equirectangular) {
        size_t size;
        AVSphericalMapping *m = av_spherical_alloc(&size);
        if (!m)
            return false;
        m->projection = AV_SPHERICAL_EQUIRECTANGULAR;
        if (av_stream_add_side_data(st, AV_PKT_DATA_SPHERICAL, (uint8_t *)m, size) < 0) {
            av_free(m);
            return false;
        }
    }
    if (view->stereo) {
        AVStereo3D *s = av_stereo3d_alloc();
        if (!s)
            return false;
        s->type = view->stereo == 1 ? AV_STEREO3D_SIDEBYSIDE : AV_STEREO3D_TOPBOTTOM;
        if (av_stream_add_side_data(st, AV_PKT_DATA_STEREO3D, (uint8_t *)s, sizeof *s) < 0) {
            av_free(s);
            return false;
        }
    }
    return true;
}

/* The encoder's context: size, rate, BT.709 limited range, constant quality. */
static bool open_encoder(video_writer *v, int width, int height, int fps, const video_options *o, err_t *err)
{
    const AVCodec *codec = NULL;
    const char *name = NULL;
    for (int i = 0; ENCODERS[o->codec][i] && !codec; i++)
        codec = avcodec_find_encoder_by_name(name = ENCODERS[o->codec][i]);
    if (!codec)
        return err_set(err, "this machine's libavcodec has no %s encoder: pick another codec (--video codec=...)",
                       ENCODERS[o->codec][0]);
    v->c = avcodec_alloc_context3(codec);
    if (!v->c)
        return err_set(err, "out of memory");
    AVCodecContext *c = v->c;
    c->width = width;
    c->height = height;
    c->time_base = (AVRational){1, fps};
    c->framerate = (AVRational){fps, 1};
    c->pix_fmt = o->yuv444 ? AV_PIX_FMT_YUV444P : AV_PIX_FMT_YUV420P;
    c->color_range = AVCOL_RANGE_MPEG;
    c->color_primaries = AVCOL_PRI_BT709;
    c->color_trc = AVCOL_TRC_IEC61966_2_1; /* the frames' sRGB curve */
    c->colorspace = AVCOL_SPC_BT709;
    c->gop_size = 2 * fps;
    c->bit_rate = 0; /* constant quality (VP9 and AV1 need it) */
    if (v->fc->oformat->flags & AVFMT_GLOBALHEADER)
        c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    char crf[16];
    snprintf(crf, sizeof crf, "%d", o->crf);
    if (av_opt_set(c->priv_data, "crf", crf, 0) < 0)
        return err_set(err, "the %s encoder takes no crf: pick another codec (--video codec=...)", name);
    if (!strcmp(name, "libx264")) {
        /* the same frames, the same stream: x264's macroblock tree gives a different stream in each process (its
         * SIMD takes paths by where memory lies: three runs, three streams; none with mbtree=0), and its frame
         * threads shape the stream, so their number is fixed rather than the machine's cores */
        av_opt_set(c->priv_data, "x264-params", "mbtree=0", 0);
        c->thread_count = 4;
    }
    if (!strcmp(name, "libaom-av1"))
        av_opt_set(c->priv_data, "cpu-used", "6", 0); /* its default (1) is some 20 times slower */
    if (!strcmp(name, "libsvtav1"))
        av_opt_set(c->priv_data, "preset", "8", 0); /* its default (10) loses 2 dB at the same crf */
    int r = avcodec_open2(c, codec, NULL);
    return r >= 0 || av_fail(err, name, r);
}

static bool open_frame(video_writer *v, err_t *err)
{
    AVCodecContext *c = v->c;
    v->frame = av_frame_alloc();
    v->pkt = av_packet_alloc();
    if (!v->frame || !v->pkt)
        return err_set(err, "out of memory");
    v->frame->format = c->pix_fmt;
    v->frame->width = c->width;
    v->frame->height = c->height;
    int r = av_frame_get_buffer(v->frame, 0);
    if (r < 0)
        return av_fail(err, "a video frame", r);
    v->sws = sws_getContext(c->width, c->height, AV_PIX_FMT_RGB24, c->width, c->height, c->pix_fmt,
                            SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT, NULL, NULL, NULL);
    if (!v->sws)
        return err_set(err, "no conversion from RGB to %s", av_get_pix_fmt_name(c->pix_fmt));
    /* BT.709 coefficients (swscale's default is BT.601), full-range RGB in, limited-range YCbCr out */
    const int *bt709 = sws_getCoefficients(SWS_CS_ITU709);
    sws_setColorspaceDetails(v->sws, bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16);
    return true;
}

video_writer *video_open(const char *path, int width, int height, int fps, const video_options *o,
                         const video_view *view, err_t *err)
{
    if (!o->yuv444 && (width % 2 || height % 2)) {
        err_set(err, "%s: yuv420p needs an even width and height (this is %dx%d): change --size, or --video "
                     "pix_fmt=yuv444p", path, width, height);
        return NULL;
    }
    av_log_set_level(AV_LOG_FATAL); /* the encoders' statistics and notes: fathom says what went wrong */
    setenv("SVT_LOG", "1", 0);       /* SVT-AV1 prints its configuration unless told (1: errors only) */
    video_writer *v = calloc(1, sizeof *v);
    int r = v ? avformat_alloc_output_context2(&v->fc, NULL, container(path), path) : AVERROR(ENOMEM);
    bool ok = r >= 0 || av_fail(err, path, r);
    ok = ok && open_encoder(v, width, height, fps, o, err) && open_frame(v, err);
    if (ok) {
        v->fc->strict_std_compliance = FF_COMPLIANCE_UNOFFICIAL; /* MP4's sv3d and st3d boxes */
        v->st = avformat_new_stream(v->fc, NULL);
        ok = v->st && avcodec_parameters_from_context(v->st->codecpar, v->c) >= 0 && tag_view(v->st, view);
        if (!ok)
            err_set(err, "%s: out of memory", path);
    }
    if (ok) {
        v->st->time_base = v->c->time_base;
        v->st->avg_frame_rate = v->c->framerate;
        r = avio_open(&v->fc->pb, path, AVIO_FLAG_WRITE);
        ok = r >= 0 || av_fail(err, path, r);
    }
    if (ok) {
        r = avformat_write_header(v->fc, NULL);
        ok = v->header = r >= 0;
        if (!ok)
            av_fail(err, path, r);
    }
    if (!ok) {
        video_abort(v);
        return NULL;
    }
    return v;
}

/* Sends a frame (NULL: the end) and writes every packet the encoder has ready. */
static bool encode(video_writer *v, const AVFrame *f, err_t *err)
{
    int r = avcodec_send_frame(v->c, f);
    if (r < 0)
        return av_fail(err, "encoding", r);
    while ((r = avcodec_receive_packet(v->c, v->pkt)) >= 0) {
        av_packet_rescale_ts(v->pkt, v->c->time_base, v->st->time_base);
        v->pkt->stream_index = v->st->index;
        r = av_interleaved_write_frame(v->fc, v->pkt);
        if (r < 0)
            return av_fail(err, "writing the video", r);
    }
    return r == AVERROR(EAGAIN) || r == AVERROR_EOF || av_fail(err, "encoding", r);
}

bool video_frame(video_writer *v, const uint8_t *rgb, err_t *err)
{
    int r = av_frame_make_writable(v->frame);
    if (r < 0)
        return av_fail(err, "a video frame", r);
    const uint8_t *src[1] = {rgb};
    int stride[1] = {3 * v->c->width};
    sws_scale(v->sws, src, stride, 0, v->c->height, v->frame->data, v->frame->linesize);
    v->frame->pts = v->pts++;
    return encode(v, v->frame, err);
}

bool video_finish(video_writer *v, err_t *err)
{
    bool ok = encode(v, NULL, err);
    int r = ok ? av_write_trailer(v->fc) : 0;
    ok = ok && (r >= 0 || av_fail(err, "finishing the video", r));
    v->header = false;
    r = avio_closep(&v->fc->pb);
    ok = ok && (r >= 0 || av_fail(err, "closing the video", r));
    video_abort(v);
    return ok;
}

void video_abort(video_writer *v)
{
    if (!v)
        return;
    if (v->fc && v->fc->pb)
        avio_closep(&v->fc->pb);
    avformat_free_context(v->fc);
    avcodec_free_context(&v->c);
    sws_freeContext(v->sws);
    av_frame_free(&v->frame);
    av_packet_free(&v->pkt);
    free(v);
}
