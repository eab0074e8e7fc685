#include "image_io.h"

#include <OpenImageIO/imageio.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unistd.h>
#include <vector>

using namespace OIIO;

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

static bool write_image(const char *path, const ImageSpec &spec, TypeDesc type, const void *pixels, err_t *err)
{
    std::string tmp = temp_path_for(path);
    auto out = ImageOutput::create(path);
    if (!out)
        return err_set(err, "cannot write '%s': no image format for this file name (%s)", path,
                       OIIO::geterror().c_str());
    if (!out->open(tmp, spec)) {
        err_set(err, "cannot write '%s': %s", path, out->geterror().c_str());
        std::remove(tmp.c_str());
        return false;
    }
    bool ok = out->write_image(type, pixels) && out->close();
    if (!ok) {
        err_set(err, "cannot write '%s': %s", path, out->geterror().c_str());
        std::remove(tmp.c_str());
        return false;
    }
    if (std::rename(tmp.c_str(), path) != 0) {
        err_set(err, "cannot write '%s': %s", path, std::strerror(errno));
        std::remove(tmp.c_str());
        return false;
    }
    return true;
}

extern "C" bool image_write_u8(const char *path, int width, int height, int channels, const uint8_t *pixels,
                               err_t *err)
{
    ImageSpec spec(width, height, channels, TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("oiio:UnassociatedAlpha", 1); /* our alpha is straight: write it as it is */
    return write_image(path, spec, TypeDesc::UINT8, pixels, err);
}

extern "C" bool image_write_f32(const char *path, int width, int height, int channels, const char *const *names,
                                const float *pixels, err_t *err)
{
    ImageSpec spec(width, height, channels, TypeDesc::FLOAT);
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
    return write_image(path, spec, TypeDesc::FLOAT, pixels, err);
}

template <typename T>
static bool read_image(const char *path, int want_channels, int *width, int *height, int *channels, T **pixels,
                       TypeDesc type, err_t *err)
{
    /* Keep colour as stored: OpenImageIO would otherwise premultiply a PNG's colour by its alpha. */
    ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = ImageInput::open(path, &config);
    if (!in)
        return err_set(err, "cannot read image '%s': %s", path, OIIO::geterror().c_str());
    const ImageSpec &spec = in->spec();
    int nc = want_channels > 0 ? want_channels : spec.nchannels;
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        return err_set(err, "image '%s' is empty", path);
    std::vector<T> file((size_t)spec.width * (size_t)spec.height * (size_t)spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, type, file.data()))
        return err_set(err, "cannot read image '%s': %s", path, in->geterror().c_str());
    size_t n = (size_t)spec.width * (size_t)spec.height;
    T *out = (T *)std::malloc(sizeof(T) * n * (size_t)nc);
    const T one = type == TypeDesc::UINT8 ? (T)255 : (T)1;
    for (size_t i = 0; i < n; i++) {
        const T *src = &file[i * (size_t)spec.nchannels];
        for (int c = 0; c < nc; c++) {
            T v;
            if (spec.nchannels <= 2) /* grey or grey+alpha */
                v = c < 3 ? src[0] : (spec.nchannels == 2 ? src[1] : one);
            else
                v = c < spec.nchannels ? src[c] : (c == 3 ? one : src[0]);
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

extern "C" bool image_read_u8(const char *path, int channels, int *width, int *height, uint8_t **pixels, err_t *err)
{
    return read_image<uint8_t>(path, channels, width, height, nullptr, pixels, TypeDesc::UINT8, err);
}

extern "C" bool image_read_f32(const char *path, int *width, int *height, int *channels, float **pixels, err_t *err)
{
    return read_image<float>(path, 0, width, height, channels, pixels, TypeDesc::FLOAT, err);
}

extern "C" bool image_can_write(const char *path, err_t *err)
{
    std::string p(path);
    size_t slash = p.find_last_of('/');
    std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : p.substr(0, slash));
    if (access(dir.c_str(), W_OK) != 0)
        return err_set(err, "cannot write '%s': folder '%s' %s; choose another --output path", path, dir.c_str(),
                       errno == ENOENT ? "does not exist" : "is not writable");
    return true;
}
