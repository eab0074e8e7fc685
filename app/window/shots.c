/* shots — views, presets, screenshots and meshes (shots.h). */
#include "window/shots.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "gpu/render.h"
#include "jobs/mesh/mesh_job.h"
#include "jobs/capture/offline.h"
#include "scene/formula/frag.h"
#include "scene/program.h"
#include "view/views.h"

shots_opened shots_views(session *s, const camera *cam, bool save, int recall, int w, int h, char *message, size_t n)
{
    char file[PATH_MAX_LEN], *text;
    err_t e;
    shots_opened r = {0};
    if (!save && !recall)
        return r;
    if (!views_file(s->scene.name, file, sizeof file, &e)) {
        snprintf(message, n, "%s", e.msg);
    } else if (save) {
        int slot = views_next_free(file);
        char name[2] = {(char)('0' + (slot ? slot : 9)), '\0'};
        strbuf d = {0};
        session_describe(s, cam, w, h, &d);
        if (views_save(file, name, d.data, &e))
            snprintf(message, n, "saved view %s (Ctrl+%s recalls it; --view %s renders it)%s", name, name, name,
                     slot ? "" : ": all nine were used, 9 replaced");
        else
            snprintf(message, n, "%s", e.msg);
        sb_free(&d);
    } else {
        char name[2] = {(char)('0' + recall), '\0'};
        bool ok = views_load(file, name, &text, &e);
        if (ok) {
            ok = session_open_shot(s, text, file, &r.cam, &r.new_file, &e);
            free(text);
        }
        r.opened = ok;
        if (ok)
            snprintf(message, n, "back at view %s", name);
        else
            snprintf(message, n, "%s", e.msg);
    }
    return r;
}

shots_opened shots_fragment_preset(session *s, int step, int *current, char *message, size_t n)
{
    shots_opened r = {0};
    const formula *f = &s->scene.fractal.formula;
    if (!step)
        return r;
    if (!s->have_scene || !program_is_fractal(s->scene.program) || !f->fragment) {
        snprintf(message, n, "J walks a Fragmentarium fragment's presets: this scene is none");
        return r;
    }
    char names[FRAG_PRESET_MAX][FRAG_PRESET_NAME_MAX];
    err_t e;
    int count = frag_presets(f->file, names, FRAG_PRESET_MAX, &e);
    if (count <= 0) {
        snprintf(message, n, "%s", count < 0 ? e.msg : "the fragment has no presets");
        return r;
    }
    int i = ((*current < 0 && step < 0 ? 0 : *current) + step + count) % count;
    strbuf text = {0};
    char path[PATH_MAX_LEN];
    snprintf(path, sizeof path, "%s", f->file); /* the session reloads the scene, and f with it */
    bool ok = frag_preset_shot(path, names[i], &text, NULL, &e) &&
              session_open_shot(s, text.data, path, &r.cam, &r.new_file, &e);
    sb_free(&text);
    r.opened = ok;
    if (ok)
        *current = i, snprintf(message, n, "preset %d of %d: %s (J next, Shift+J previous)", i + 1, count, names[i]);
    else
        snprintf(message, n, "%s", e.msg);
    return r;
}

shots_opened shots_presets(GLFWwindow *win, session *s, const camera *cam, shots_preset_ask ask, const char *path,
                           int w, int h, char *message, size_t n)
{
    err_t e;
    shots_opened r = {0};
    if (ask.save || ask.copy) {
        strbuf d = {0};
        session_describe(s, cam, w, h, &d);
        if (ask.copy) {
            glfwSetClipboardString(win, d.data);
            snprintf(message, n, "copied the preset (scene, edits, camera) to the clipboard");
        }
        if (ask.save && util_write_text_atomic(path, d.data, "the preset", &e))
            snprintf(message, n, "saved %.900s: fathom --scene %.900s opens it anywhere", path, path);
        else if (ask.save)
            snprintf(message, n, "%s", e.msg);
        sb_free(&d);
    }
    if (ask.load || ask.paste) {
        char *text = NULL;
        const char *clip = ask.paste ? glfwGetClipboardString(win) : NULL;
        bool ok = ask.paste ? clip != NULL : util_read_file(path, &text, NULL, &e);
        if (ask.paste && !ok)
            err_set(&e, "the clipboard holds no text");
        ok = ok && session_open_shot(s, ask.paste ? clip : text, ask.paste ? "the clipboard" : path, &r.cam, &r.new_file, &e);
        free(text);
        snprintf(message, n, "%s", ok ? "opened the preset" : e.msg);
        r.opened = ok;
    }
    return r;
}

void shots_screenshot(const session *s, const camera *cam, int w, int h, char *message, size_t n)
{
    int aw, ah;
    render_active_size(&aw, &ah);
    if (aw != w || ah != h) { /* a moving (smaller) image: drawn once at full size */
        render_set_active(w, h);
        render_begin(cam);
        render_sample();
    } else if (render_band_rows() > 0) { /* a sample in progress: finished first */
        render_sample_band(h);
    }
    char file[128];
    time_t now = time(NULL);
    strftime(file, sizeof file, "fathom-%Y%m%d-%H%M%S.png", localtime(&now));
    err_t err;
    strbuf description = {0}; /* the shot remembers how it was made */
    session_describe(s, cam, w, h, &description);
    bool ok = offline_write(file, w, h, 0, description.data, &err);
    sb_free(&description);
    if (ok)
        snprintf(message, n, "saved %s (%d samples)", file, render_samples());
    else
        snprintf(message, n, "%s", err.msg);
    fprintf(stderr, "fathom: %s\n", message);
}

void shots_mesh(const session *s, char *message, size_t n)
{
    char file[128];
    time_t now = time(NULL);
    strftime(file, sizeof file, "fathom-%Y%m%d-%H%M%S.glb", localtime(&now));
    mesh_desc d = {.scene = s->scene.path, .output = file};
    err_t err;
    if (mesh_job_scene(&d, &s->scene, &err))
        snprintf(message, n, "saved %s: the scene's surface at %d cells (fathom mesh for more)", file, MESH_JOB_DEFAULT_RES);
    else
        snprintf(message, n, "%s", err.msg);
    fprintf(stderr, "fathom: %s\n", message);
}
