/* image_io.cpp — fathom_image.so: OpenImageIO behind data/media/image_oiio.h (image_io.c loads it on first
 * use). Every extern "C" function catches what OpenImageIO or the standard library may throw
 * (std::bad_alloc above all) and turns it into an err_t. */
#include "data/media/image_oiio.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

using namespace OIIO;

/* ---- decoders write to stderr (libpng: "libpng error: …"): catch it and fold it into our line ---- */

class StderrCapture
{
  public:
    StderrCapture()
    {
        std::fflush(stderr);
        file_ = std::tmpfile();
        saved_ = file_ ? dup(2) : -1;
        if (saved_ >= 0)
            dup2(fileno(file_), 2);
    }
    ~StderrCapture() { restore(); }
    /* What was written, on one line. */
    std::string text()
    {
        restore();
        std::string s;
        if (!file_)
            return s;
        std::rewind(file_);
        char buf[512];
        size_t n = std::fread(buf, 1, sizeof buf - 1, file_);
        s.assign(buf, n);
        std::replace(s.begin(), s.end(), '\n', ' ');
        while (!s.empty() && s.back() == ' ')
            s.pop_back();
        return s;
    }

  private:
    void restore()
    {
        if (saved_ >= 0) {
            std::fflush(stderr);
            dup2(saved_, 2);
            close(saved_);
            saved_ = -1;
        }
    }
    FILE *file_ = nullptr;
    int saved_ = -1;

  public:
    StderrCapture(const StderrCapture &) = delete;
    StderrCapture &operator=(const StderrCapture &) = delete;
};

/* OpenImageIO's messages may hold several lines: ours is one. */
static std::string one_line(std::string s)
{
    for (size_t i; (i = s.find('\n')) != std::string::npos;)
        s.replace(i, 1, i + 1 < s.size() ? "; " : "");
    return s;
}

static std::string with_noise(std::string msg, StderrCapture &noise)
{
    msg = one_line(msg);
    std::string extra = noise.text();
    if (!extra.empty() && msg.find(extra) == std::string::npos)
        msg += msg.empty() ? extra : " (" + extra + ")";
    return msg.empty() ? "unknown error" : msg;
}

/* ---- writing (to the temporary file image_io.c names) ------------------------------------------ */

struct oiio_writer {
    std::string path;
    std::unique_ptr<ImageOutput> out;
    ImageSpec spec;
    TypeDesc type;
};

static ImageSpec make_spec(int width, int height, int channels, bool f32, const char *const *names)
{
    ImageSpec spec(width, height, channels, f32 ? TypeDesc::FLOAT : TypeDesc::UINT8);
    if (!f32) {
        spec.attribute("oiio:ColorSpace", "sRGB");
        spec.attribute("oiio:UnassociatedAlpha", 1); /* our alpha is straight: write it as it is */
        return spec;
    }
    if (names) {
        spec.channelnames.clear();
        for (int i = 0; i < channels; i++)
            spec.channelnames.emplace_back(names[i]);
        spec.alpha_channel = -1;
        spec.z_channel = -1;
        for (int i = 0; i < channels; i++) {
            if (spec.channelnames[i] == "A")
                spec.alpha_channel = i;
            if (spec.channelnames[i] == "Z")
                spec.z_channel = i;
        }
    }
    spec.attribute("compression", "zip");
    spec.attribute("oiio:ColorSpace", "Linear");
    return spec;
}

/* A text entry as an attribute: "m44f:NAME" with 16 numbers is a 4×4 matrix (OpenEXR's worldToCamera
 * and worldToNDC: OpenImageIO's worldtocamera and worldtoNDC), anything else a string. */
static void text_attribute(ImageSpec &spec, const char *key, const char *value)
{
    if (std::strncmp(key, "m44f:", 5) != 0) {
        spec.attribute(key, value);
        return;
    }
    float m[16];
    int used = 0;
    for (int k = 0; k < 16; k++) {
        int n = 0;
        if (std::sscanf(value + used, "%f%n", &m[k], &n) != 1)
            return; /* not 16 numbers: fathom's own text, so never */
        used += n;
    }
    spec.attribute(key + 5, TypeMatrix44, m);
}

extern "C" oiio_writer *oiio_writer_open(const char *path, const char *tmp, int width, int height, int channels,
                                         bool f32, const char *const *names, const char *const *texts, err_t *err)
{
    oiio_writer *w = nullptr;
    try {
        w = new oiio_writer;
        w->path = path;
        w->type = f32 ? TypeDesc::FLOAT : TypeDesc::UINT8;
        w->spec = make_spec(width, height, channels, f32, names);
        for (int i = 0; texts && texts[i]; i += 2)
            if (texts[i + 1])
                text_attribute(w->spec, texts[i], texts[i + 1]);
        w->out = ImageOutput::create(path);
        if (!w->out) {
            err_set(err, "cannot write '%s': no image format for this file name (%s)", path, one_line(OIIO::geterror()).c_str());
            delete w;
            return nullptr;
        }
        if (!w->out->open(tmp, w->spec)) {
            err_set(err, "cannot write '%s': %s", path, one_line(w->out->geterror()).c_str());
            delete w;
            return nullptr;
        }
        return w;
    } catch (const std::exception &e) {
        err_set(err, "cannot write '%s': %s", path, e.what());
        delete w;
        return nullptr;
    }
}

extern "C" bool oiio_writer_rows(oiio_writer *w, int first_row, int rows, const void *pixels, err_t *err)
{
    try {
        if (!w->out->write_scanlines(first_row, first_row + rows, 0, w->type, pixels))
            return err_set(err, "cannot write '%s': %s", w->path.c_str(), one_line(w->out->geterror()).c_str());
        return true;
    } catch (const std::exception &e) {
        return err_set(err, "cannot write '%s': %s", w->path.c_str(), e.what());
    }
}

extern "C" bool oiio_writer_close(oiio_writer *w, err_t *err)
{
    bool ok = false;
    try {
        ok = w->out->close() || err_set(err, "%s", one_line(w->out->geterror()).c_str());
    } catch (const std::exception &e) {
        err_set(err, "%s", e.what());
    }
    delete w;
    return ok;
}

/* Decodes every row in bands: a truncated or corrupt file fails here. */
extern "C" bool oiio_verify(const char *file, int width, int height, int channels, err_t *err)
{
    try {
        StderrCapture noise;
        auto in = ImageInput::open(file);
        if (!in)
            return err_set(err, "%s", with_noise(OIIO::geterror(), noise).c_str());
        const ImageSpec &s = in->spec();
        if (s.width != width || s.height != height || s.nchannels != channels)
            return err_set(err, "it reads back as %dx%d with %d channels", s.width, s.height, s.nchannels);
        const int band = std::max(1, (int)(((size_t)16 << 20) / ((size_t)s.width * (size_t)s.nchannels * 4)));
        std::vector<float> buf((size_t)band * (size_t)s.width * (size_t)s.nchannels);
        for (int y = 0; y < s.height; y += band) {
            int y1 = std::min(s.height, y + band);
            if (!in->read_scanlines(0, 0, y, y1, 0, 0, s.nchannels, TypeDesc::FLOAT, buf.data()))
                return err_set(err, "%s", with_noise(in->geterror(), noise).c_str());
        }
        return true;
    } catch (const std::exception &e) {
        return err_set(err, "%s", e.what());
    }
}

/* ---- reading ------------------------------------------------------------------------------------ */

extern "C" bool oiio_read_text(const char *path, const char *key, char **value, err_t *err)
{
    try {
        StderrCapture noise;
        auto in = ImageInput::open(path);
        if (!in)
            return err_set(err, "cannot read image '%s': %s", path, with_noise(OIIO::geterror(), noise).c_str());
        const ParamValue *p = in->spec().find_attribute(key);
        std::string v = p && p->type() == TypeMatrix44 ? in->spec().metadata_val(*p) : std::string(in->spec().get_string_attribute(key));
        if (v.empty())
            return err_set(err, "image '%s' holds no fathom shot description (only PNG and EXR files fathom "
                                "wrote do)", path);
        *value = (char *)std::malloc(v.size() + 1);
        if (!*value)
            return err_set(err, "cannot read image '%s': out of memory", path);
        std::memcpy(*value, v.c_str(), v.size() + 1);
        return true;
    } catch (const std::exception &e) {
        return err_set(err, "cannot read image '%s': %s", path, e.what());
    }
}

template <typename T>
static bool read_image(const char *path, int want_channels, int max_side, int *width, int *height, int *channels,
                       T **pixels, TypeDesc type, err_t *err)
{
    StderrCapture noise;
    /* Keep colour as stored: OpenImageIO would otherwise premultiply a PNG's colour by its alpha. */
    ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = ImageInput::open(path, &config);
    if (!in)
        return err_set(err, "cannot read image '%s': %s", path, with_noise(OIIO::geterror(), noise).c_str());
    const ImageSpec &spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        return err_set(err, "image '%s' is empty", path);
    if (spec.width > max_side || spec.height > max_side || spec.depth > 1)
        return err_set(err, "image '%s' is %dx%d%s: larger than the %dx%d fathom can use here; scale it "
                            "down", path, spec.width, spec.height, spec.depth > 1 ? " (a volume)" : "", max_side,
                       max_side);
    int nc = want_channels > 0 ? want_channels : spec.nchannels;
    int nread = std::min(nc, spec.nchannels); /* only the channels used are read */
    if (spec.nchannels == 2 && nc >= 3)
        nread = 2; /* grey + alpha: both are needed to fill colour and alpha */
    size_t n = (size_t)spec.width * (size_t)spec.height;
    /* what reading takes, against the machine's memory, before anything is allocated: a small file's
     * header may claim any size */
    double need = (double)sizeof(T) * (double)n * (double)(nread + nc);
    if (need > util_physical_memory())
        return err_set(err, "image '%s' is %dx%d: reading it takes %.1f GB and this machine has %.1f GB; scale it down",
                       path, spec.width, spec.height, need / 1e9, util_physical_memory() / 1e9);
    /* rows in blocks into memory the kernel commits as it is written: a file whose data stops short
     * (a forged header) fails at its first missing block, not after touching the whole image */
    std::unique_ptr<T, decltype(&std::free)> file((T *)std::malloc(sizeof(T) * n * (size_t)nread), &std::free);
    T *out = (T *)std::malloc(sizeof(T) * n * (size_t)nc);
    if (!file || !out) {
        std::free(out);
        return err_set(err, "cannot read image '%s' (%dx%d): out of memory", path, spec.width, spec.height);
    }
    const int ROWS = 64;
    for (int y = 0; y < spec.height; y += ROWS) {
        int y1 = std::min(spec.height, y + ROWS);
        if (!in->read_scanlines(0, 0, spec.y + y, spec.y + y1, 0, 0, nread, type,
                                file.get() + (size_t)y * (size_t)spec.width * (size_t)nread)) {
            std::free(out);
            return err_set(err, "cannot read image '%s': %s", path, with_noise(in->geterror(), noise).c_str());
        }
    }
    const T one = type == TypeDesc::UINT8 ? (T)255 : (T)1;
    for (size_t i = 0; i < n; i++) {
        const T *src = file.get() + i * (size_t)nread;
        for (int c = 0; c < nc; c++) {
            T v;
            if (spec.nchannels <= 2) /* grey or grey+alpha */
                v = c < 3 ? src[0] : (nread == 2 ? src[1] : one);
            else
                v = c < nread ? src[c] : (c == 3 ? one : src[0]);
            out[i * (size_t)nc + (size_t)c] = v;
        }
    }
    *width = spec.width;
    *height = spec.height;
    if (channels)
        *channels = nc;
    *pixels = out;
    return true;
}

template <typename T>
static bool read_caught(const char *path, int want, int max_side, int *width, int *height, int *channels, T **px,
                        TypeDesc type, err_t *err)
{
    try {
        return read_image<T>(path, want, max_side, width, height, channels, px, type, err);
    } catch (const std::bad_alloc &) {
        return err_set(err, "cannot read image '%s': out of memory", path);
    } catch (const std::exception &e) {
        return err_set(err, "cannot read image '%s': %s", path, e.what());
    }
}

extern "C" bool oiio_read_u8(const char *path, int channels, int max_side, int *width, int *height,
                              uint8_t **pixels, err_t *err)
{
    return read_caught<uint8_t>(path, channels, max_side, width, height, nullptr, pixels, TypeDesc::UINT8, err);
}

extern "C" bool oiio_read_f32(const char *path, int channels, int max_side, int *width, int *height,
                               int *channels_out, float **pixels, err_t *err)
{
    return read_caught<float>(path, channels, max_side, width, height, channels_out, pixels, TypeDesc::FLOAT, err);
}
