/* image_io — see image_io.h. Every extern "C" function catches what OpenImageIO or the standard
 * library may throw (std::bad_alloc above all) and turns it into an err_t. */
#include "data/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <fcntl.h>
#include <memory>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

using namespace OIIO;

/* ---- the temporary file of the write in progress, for the signal handler ------------------------- */

static char g_temp[PATH_MAX_LEN];         /* written only while no signal can see it half done: */
static volatile sig_atomic_t g_temp_live; /* the handler reads g_temp only when this is 1 */

static void set_temp(const std::string &path)
{
    g_temp_live = 0;
    std::snprintf(g_temp, sizeof g_temp, "%s", path.c_str());
    g_temp_live = 1;
}

static void clear_temp(void) { g_temp_live = 0; }

extern "C" void on_fatal_signal(int sig)
{
    if (g_temp_live)
        unlink(g_temp); /* async-signal-safe */
    std::signal(sig, SIG_DFL);
    raise(sig);
}

static void at_exit(void)
{
    if (g_temp_live)
        unlink(g_temp);
}

extern "C" void image_io_install_signal_cleanup(void)
{
    std::atexit(at_exit); /* util_alloc's exit on out-of-memory */
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT})
        std::signal(sig, on_fatal_signal);
    std::signal(SIGXFSZ, SIG_IGN); /* over a file-size limit, write() fails with EFBIG instead */
}

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

/* ---- writing ------------------------------------------------------------------------------------ */

struct image_writer {
    std::string path, tmp;
    std::unique_ptr<ImageOutput> out;
    ImageSpec spec;
    TypeDesc type;
    int next_row = 0;
};

static std::string temp_path_for(const std::string &path)
{
    /* Same folder (rename stays atomic), same extension (OpenImageIO picks the format from it). */
    size_t slash = path.find_last_of('/');
    std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    size_t dot = base.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : base.substr(dot);
    return dir + "." + base + ".tmp" + std::to_string(getpid()) + ext;
}

extern "C" int image_remove_stale_temps(const char *path)
{
    const char *slash = std::strrchr(path, '/');
    std::string dir = slash ? std::string(path, (size_t)(slash - path) + 1) : std::string("./");
    DIR *d = opendir(dir.c_str());
    if (!d)
        return 0;
    int removed = 0;
    while (struct dirent *e = readdir(d)) {
        /* ".NAME.tmpPID.EXT", as temp_path_for makes it, whose writer is gone */
        const char *n = e->d_name, *t = n[0] == '.' ? std::strstr(n, ".tmp") : nullptr;
        while (t && std::strstr(t + 1, ".tmp"))
            t = std::strstr(t + 1, ".tmp");
        if (!t || t == n)
            continue;
        char *end;
        long pid = std::strtol(t + 4, &end, 10);
        if (end == t + 4 || *end != '.' || pid <= 0 || std::strchr(end + 1, '.') || pid == (long)getpid())
            continue;
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH)
            continue; /* its writer is alive (or not ours to ask): leave it */
        if (std::remove((dir + n).c_str()) == 0)
            removed++;
    }
    closedir(d);
    return removed;
}

static void discard(image_writer *w)
{
    if (w->out)
        w->out->close();
    std::remove(w->tmp.c_str());
    clear_temp();
    delete w;
}

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

extern "C" image_writer *image_writer_open(const char *path, int width, int height, int channels, bool f32,
                                           const char *const *names, err_t *err)
{
    return image_writer_open_text(path, width, height, channels, f32, names, nullptr, err);
}

extern "C" image_writer *image_writer_open_text(const char *path, int width, int height, int channels, bool f32,
                                                const char *const *names, const char *const *texts, err_t *err)
{
    image_writer *w = nullptr;
    try {
        w = new image_writer;
        w->path = path;
        w->tmp = temp_path_for(path);
        w->type = f32 ? TypeDesc::FLOAT : TypeDesc::UINT8;
        w->spec = make_spec(width, height, channels, f32, names);
        for (int i = 0; texts && texts[i]; i += 2)
            if (texts[i + 1])
                w->spec.attribute(texts[i], texts[i + 1]);
        w->out = ImageOutput::create(path);
        if (!w->out) {
            err_set(err, "cannot write '%s': no image format for this file name (%s)", path, one_line(OIIO::geterror()).c_str());
            delete w;
            return nullptr;
        }
        set_temp(w->tmp);
        if (!w->out->open(w->tmp, w->spec)) {
            err_set(err, "cannot write '%s': %s", path, one_line(w->out->geterror()).c_str());
            w->out.reset();
            discard(w);
            return nullptr;
        }
        return w;
    } catch (const std::exception &e) {
        err_set(err, "cannot write '%s': %s", path, e.what());
        if (w)
            discard(w);
        return nullptr;
    }
}

extern "C" bool image_writer_rows(image_writer *w, int rows, const void *pixels, err_t *err)
{
    try {
        if (w->next_row + rows > w->spec.height)
            return err_set(err, "cannot write '%s': %d rows past the image's %d", w->path.c_str(),
                           w->next_row + rows - w->spec.height, w->spec.height);
        if (!w->out->write_scanlines(w->next_row, w->next_row + rows, 0, w->type, pixels))
            return err_set(err, "cannot write '%s': %s", w->path.c_str(), one_line(w->out->geterror()).c_str());
        w->next_row += rows;
        return true;
    } catch (const std::exception &e) {
        return err_set(err, "cannot write '%s': %s", w->path.c_str(), e.what());
    }
}

/* The bytes on the disk, not in a cache: a failure here (EIO, ENOSPC on some file systems) is the last
 * chance to hear of it. */
static bool sync_file(const std::string &path, int flags)
{
    int fd = open(path.c_str(), flags);
    if (fd < 0)
        return false;
    bool ok = fsync(fd) == 0 || errno == EINVAL; /* EINVAL: a folder on a file system without fsync */
    close(fd);
    return ok;
}

/* Decodes every row of the written file in bands: a truncated or corrupt file fails here. */
static bool verify(const image_writer *w, std::string *why)
{
    StderrCapture noise;
    auto in = ImageInput::open(w->tmp);
    if (!in) {
        *why = with_noise(OIIO::geterror(), noise);
        return false;
    }
    const ImageSpec &s = in->spec();
    if (s.width != w->spec.width || s.height != w->spec.height || s.nchannels != w->spec.nchannels) {
        *why = "it reads back as " + std::to_string(s.width) + "x" + std::to_string(s.height) + " with " +
               std::to_string(s.nchannels) + " channels";
        return false;
    }
    const int band = std::max(1, (int)(((size_t)16 << 20) / ((size_t)s.width * (size_t)s.nchannels * 4)));
    std::vector<float> buf((size_t)band * (size_t)s.width * (size_t)s.nchannels);
    for (int y = 0; y < s.height; y += band) {
        int y1 = std::min(s.height, y + band);
        if (!in->read_scanlines(0, 0, y, y1, 0, 0, s.nchannels, TypeDesc::FLOAT, buf.data())) {
            *why = with_noise(in->geterror(), noise);
            return false;
        }
    }
    return true;
}

extern "C" bool image_writer_finish(image_writer *w, err_t *err)
{
    try {
        const char *path = w->path.c_str();
        if (w->next_row != w->spec.height) {
            err_set(err, "cannot write '%s': only %d of %d rows were rendered", path, w->next_row, w->spec.height);
            discard(w);
            return false;
        }
        bool closed = w->out->close();
        std::string why = closed ? "" : one_line(w->out->geterror());
        w->out.reset();
        errno = 0;
        if (closed && !sync_file(w->tmp, O_RDONLY))
            closed = false, why = std::strerror(errno);
        if (!closed || !verify(w, &why)) {
            err_set(err, "cannot write '%s': %s%s", path,
                    closed ? "the file did not read back after writing (disk full or file too large?): " : "",
                    why.empty() ? "write failed" : why.c_str());
            discard(w);
            return false;
        }
        if (std::rename(w->tmp.c_str(), path) != 0) {
            err_set(err, "cannot write '%s': %s", path, std::strerror(errno));
            discard(w);
            return false;
        }
        clear_temp();
        size_t slash = w->path.find_last_of('/');
        sync_file(slash == std::string::npos ? "." : w->path.substr(0, slash + 1), O_RDONLY | O_DIRECTORY);
        delete w;
        return true;
    } catch (const std::exception &e) {
        err_set(err, "cannot write '%s': %s", w->path.c_str(), e.what());
        discard(w);
        return false;
    }
}

extern "C" void image_writer_abort(image_writer *w)
{
    try {
        discard(w);
    } catch (const std::exception &) {
    }
}

static bool write_whole(const char *path, int width, int height, int channels, bool f32, const char *const *names,
                        const void *pixels, err_t *err)
{
    image_writer *w = image_writer_open(path, width, height, channels, f32, names, err);
    if (!w)
        return false;
    if (!image_writer_rows(w, height, pixels, err)) {
        image_writer_abort(w);
        return false;
    }
    return image_writer_finish(w, err);
}

extern "C" bool image_write_u8(const char *path, int width, int height, int channels, const uint8_t *pixels,
                               err_t *err)
{
    return write_whole(path, width, height, channels, false, nullptr, pixels, err);
}

extern "C" bool image_write_f32(const char *path, int width, int height, int channels, const char *const *names,
                                const float *pixels, err_t *err)
{
    return write_whole(path, width, height, channels, true, names, pixels, err);
}

/* ---- reading ------------------------------------------------------------------------------------ */

extern "C" bool image_read_text(const char *path, const char *key, char **value, err_t *err)
{
    try {
        StderrCapture noise;
        auto in = ImageInput::open(path);
        if (!in)
            return err_set(err, "cannot read image '%s': %s", path, with_noise(OIIO::geterror(), noise).c_str());
        std::string v = in->spec().get_string_attribute(key);
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
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0 && need > (double)pages * (double)page)
        return err_set(err, "image '%s' is %dx%d: reading it takes %.1f GB and this machine has %.1f GB; scale it down",
                       path, spec.width, spec.height, need / 1e9, (double)pages * (double)page / 1e9);
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

extern "C" bool image_read_u8(const char *path, int channels, int max_side, int *width, int *height,
                              uint8_t **pixels, err_t *err)
{
    return read_caught<uint8_t>(path, channels, max_side, width, height, nullptr, pixels, TypeDesc::UINT8, err);
}

extern "C" bool image_read_f32(const char *path, int channels, int max_side, int *width, int *height,
                               int *channels_out, float **pixels, err_t *err)
{
    return read_caught<float>(path, channels, max_side, width, height, channels_out, pixels, TypeDesc::FLOAT, err);
}
