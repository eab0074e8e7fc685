#include "gpu/gpu.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_EGL_DEVICES = 16 };

static struct {
    GLFWwindow *window;
    EGLDisplay dpy;
    EGLContext ctx;
    char describe[512];
    char glfw_error[512];
} state = {.dpy = EGL_NO_DISPLAY, .ctx = EGL_NO_CONTEXT};

static void on_glfw_error(int code, const char *msg)
{
    (void)code;
    snprintf(state.glfw_error, sizeof state.glfw_error, "%s", msg);
}

static bool open_window(const gpu_desc *d, err_t *err)
{
    const char *x = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
    if ((!x || !*x) && (!wl || !*wl))
        return err_set(err, "no display to open a window on (DISPLAY is not set): render offline with "
                            "--output shot.png, or run under xvfb-run -a");
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit())
        return err_set(err, "cannot open a window: %s (render offline with --output shot.png)", state.glfw_error);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    state.window = glfwCreateWindow(d->width ? d->width : GPU_DEFAULT_WIDTH, d->height ? d->height : GPU_DEFAULT_HEIGHT,
                                    d->title ? d->title : "fathom", NULL, NULL);
    if (!state.window) {
        glfwTerminate();
        return err_set(err, "cannot create an OpenGL 3.3 core window: %s", state.glfw_error);
    }
    glfwMakeContextCurrent(state.window);
    glfwSwapInterval(0); /* frame times are the point of the HUD: no vsync cap */
    snprintf(state.describe, sizeof state.describe, "GLFW window · %s · %s", (const char *)glGetString(GL_RENDERER),
             (const char *)glGetString(GL_VERSION));
    return true;
}

/* A hardware EGL device (skips Mesa's software device, which surfaceless covers). *hardware counts
 * the hardware devices seen. Device enumeration comes as EGL_EXT_device_enumeration (Mesa) or inside
 * EGL_EXT_device_base (NVIDIA's driver advertises only that one). */
static EGLDisplay device_display(int wanted, int *hardware)
{
    *hardware = 0;
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device") ||
        !(epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") ||
          epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base")))
        return EGL_NO_DISPLAY;
    EGLDeviceEXT devices[MAX_EGL_DEVICES];
    EGLint n = 0;
    if (!eglQueryDevicesEXT(MAX_EGL_DEVICES, devices, &n))
        return EGL_NO_DISPLAY;
    /* wanted = K: the K-th hardware device (farms whose scheduler does not hide the other GPUs); −1:
     * the first that initialises (a task confined to its GPU by cgroups gets that one) */
    int hardware_index = -1;
    for (EGLint i = 0; i < n; i++) {
        const char *ext = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
        if (ext && strstr(ext, "EGL_MESA_device_software"))
            continue;
        ++*hardware;
        if (++hardware_index != wanted && wanted >= 0)
            continue;
        EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
        if (dpy != EGL_NO_DISPLAY && eglInitialize(dpy, NULL, NULL))
            return dpy;
    }
    return EGL_NO_DISPLAY;
}

static bool open_headless(err_t *err)
{
    /* The EXT entry point: libepoxy aborts on EGL 1.5's eglGetPlatformDisplay before a display exists. */
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base"))
        return err_set(err, "headless rendering needs EGL_EXT_platform_base: install Mesa's EGL (libegl-mesa0)");
    const char *platform = "EGL device", *want = getenv("FATHOM_EGL_DEVICE");
    char *end = NULL;
    long wanted = want && *want ? strtol(want, &end, 10) : -1;
    if (want && *want && (*end || wanted < 0 || wanted > 1000000))
        return err_set(err, "FATHOM_EGL_DEVICE='%s' is not a device number (0, 1, ...): unset it to take the first GPU",
                       want);
    int hardware;
    state.dpy = device_display((int)wanted, &hardware);
    if (state.dpy == EGL_NO_DISPLAY && wanted >= 0) /* asked for a GPU: never fall back to software quietly */
        return err_set(err, "FATHOM_EGL_DEVICE=%ld: no such hardware EGL device that initialises (%d found): "
                            "number them from 0, or unset it", wanted, hardware);
    if (state.dpy == EGL_NO_DISPLAY) {
        platform = "EGL surfaceless";
        if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
            return err_set(err, "no headless EGL platform (device or Mesa surfaceless): install libegl-mesa0 "
                                "and libgl1-mesa-dri");
        state.dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
        if (state.dpy == EGL_NO_DISPLAY || !eglInitialize(state.dpy, NULL, NULL))
            return err_set(err, "cannot initialise EGL surfaceless (error 0x%x): is libgl1-mesa-dri installed?",
                           eglGetError());
    }
    if (!eglBindAPI(EGL_OPENGL_API))
        return err_set(err, "%s: desktop OpenGL is not available", platform);
    /* EGL_SURFACE_TYPE defaults to windows, which surfaceless has none of */
    static const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig cfg;
    EGLint ncfg = 0;
    if (!eglChooseConfig(state.dpy, cfg_attr, &cfg, 1, &ncfg) || ncfg < 1)
        return err_set(err, "%s: no OpenGL config", platform);
    static const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    state.ctx = eglCreateContext(state.dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (state.ctx == EGL_NO_CONTEXT)
        return err_set(err, "%s: cannot create an OpenGL 3.3 core context (error 0x%x)", platform, eglGetError());
    if (!eglMakeCurrent(state.dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, state.ctx))
        return err_set(err, "%s: cannot make the context current without a surface (error 0x%x)", platform,
                       eglGetError());
    snprintf(state.describe, sizeof state.describe, "%s · %s · %s", platform, (const char *)glGetString(GL_RENDERER),
             (const char *)glGetString(GL_VERSION));
    return true;
}

bool gpu_open(const gpu_desc *d, err_t *err)
{
    bool ok = d->headless ? open_headless(err) : open_window(d, err);
    if (!ok)
        gpu_close();
    return ok;
}

void gpu_close(void)
{
    if (state.window) {
        glfwDestroyWindow(state.window);
        glfwTerminate();
        state.window = NULL;
    }
    if (state.dpy != EGL_NO_DISPLAY) {
        eglMakeCurrent(state.dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (state.ctx != EGL_NO_CONTEXT)
            eglDestroyContext(state.dpy, state.ctx);
        eglTerminate(state.dpy);
        state.dpy = EGL_NO_DISPLAY;
        state.ctx = EGL_NO_CONTEXT;
    }
}

const char *gpu_describe(void) { return state.describe; }
GLFWwindow *gpu_window(void) { return state.window; }
