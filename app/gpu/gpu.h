/* gpu — the GL 3.3 core context, from a GLFW window or headless EGL. The rest of fathom only sees
 * "a current GL context"; the renderer does not know which backend made it.
 *
 * Headless order: the EGL device platform on a hardware device (real GPU drivers), else Mesa's
 * surfaceless platform (llvmpipe on machines without a GPU). GLFW is never initialised headless,
 * because GLFW 3.3 cannot start without a display.
 */
#ifndef FATHOM_GPU_H
#define FATHOM_GPU_H

#include <stdbool.h>

#include "util.h"

typedef struct GLFWwindow GLFWwindow;

/* The size of a window and of an image when none is given (--size): every default size is this one. */
enum { GPU_DEFAULT_WIDTH = FATHOM_DEFAULT_WIDTH, GPU_DEFAULT_HEIGHT = FATHOM_DEFAULT_HEIGHT };

typedef struct gpu_desc {
    bool headless;
    int width, height; /* window size; 0: GPU_DEFAULT_WIDTH x GPU_DEFAULT_HEIGHT */
    const char *title;
} gpu_desc;

bool gpu_open(const gpu_desc *d, err_t *err);
void gpu_close(void);

/* "EGL surfaceless · llvmpipe (LLVM 15.0.6, 256 bits) · 4.5 (Core Profile) Mesa 22.3.6" */
const char *gpu_describe(void);

/* The window, or NULL headless. */
GLFWwindow *gpu_window(void);

#endif
