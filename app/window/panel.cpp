/* panel — see panel.h. Dear ImGui 1.86 (Debian's libimgui-dev) with its GLFW and OpenGL 3 backends. */
#include "window/panel.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

const float PANEL_WIDTH = 420.0f;
const double DEG = 3.14159265358979323846 / 180.0;
const char *const MODE_NAMES[CAMERA_MODE_COUNT] = {"fly", "orbit", "walk"};
const char *const VIEW_NAMES[] = {"colour", "steps (heat map)", "difference to the grabbed frame"};

struct {
    bool ready;
    char set[PANEL_SET_MAX];
    char preset[PANEL_PATH_MAX];
    bool preset_named; /* the user typed a path: keep it */
    double typed_position[3], typed_look_at[3];
    float typed_fov;
    bool typed_valid;
} state;

/* Turns the control's new value into an override (and an undo step when the user took hold of it). */
void edited(const param_list *l, const scene_param *p, const double v[3], panel_actions *out)
{
    params_override(l, p, v, out->set, sizeof out->set);
}

void note_activation(panel_actions *out)
{
    if (ImGui::IsItemActivated())
        out->edit_started = true;
}

void tooltip(const scene_param *p)
{
    if (!ImGui::IsItemHovered())
        return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
    ImGui::TextUnformatted(p->key);
    if (p->help[0])
        ImGui::TextUnformatted(p->help);
    if (p->type != PARAM_BOOL && p->type != PARAM_ENUM)
        ImGui::Text("range %g to %g (Ctrl+click to type a value)", p->lo, p->hi);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

/* A direction as two angles: the azimuth about Y (0 toward +X) and the elevation above the XZ plane. */
bool direction_control(const char *label, double v[3])
{
    double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(len > 0))
        len = 1;
    float az = (float)(std::atan2(v[2], v[0]) / DEG), el = (float)(std::asin(std::clamp(v[1] / len, -1.0, 1.0)) / DEG);
    ImGui::PushID(label);
    bool changed = ImGui::SliderFloat("##az", &az, -180.0f, 180.0f, "azimuth %.1f deg");
    changed |= ImGui::SliderFloat("##el", &el, -90.0f, 90.0f, "elevation %.1f deg");
    ImGui::PopID();
    if (changed) {
        v[0] = std::cos(el * DEG) * std::cos(az * DEG);
        v[1] = std::sin(el * DEG);
        v[2] = std::cos(el * DEG) * std::sin(az * DEG);
    }
    return changed;
}

bool ends_with(const char *s, const char *tail)
{
    size_t a = std::strlen(s), b = std::strlen(tail);
    return a >= b && !std::strcmp(s + a - b, tail);
}

/* A slider over a short range, a drag over a wide one (speed from the value's own size). */
bool number_control(const char *label, const scene_param *p, double *v)
{
    if (p->type == PARAM_INT) {
        int i = (int)*v;
        bool changed = p->hi - p->lo <= 1000 ? ImGui::SliderInt(label, &i, (int)p->lo, (int)p->hi)
                                             : ImGui::DragInt(label, &i, std::max(1.0f, std::fabs((float)i) * 0.02f),
                                                              (int)p->lo, (int)p->hi);
        *v = i;
        return changed;
    }
    float f = (float)*v;
    bool changed;
    if (p->hi - p->lo <= 100) {
        ImGuiSliderFlags log = p->lo > 0 && p->hi / p->lo >= 100 ? ImGuiSliderFlags_Logarithmic : 0;
        changed = ImGui::SliderFloat(label, &f, (float)p->lo, (float)p->hi, "%.4g", log);
    } else {
        float speed = std::max(std::fabs(f), 1e-3f) * 0.01f;
        changed = ImGui::DragFloat(label, &f, speed, (float)p->lo, (float)p->hi, "%.5g", ImGuiSliderFlags_AlwaysClamp);
    }
    *v = f;
    return changed;
}

void cost_line(const panel_model *m, const scene_param *p)
{
    for (int i = 0; i < m->cost_count; i++) {
        const panel_cost *c = &m->costs[i];
        if (std::strcmp(c->key, p->key) || c->ms_after <= 0)
            continue;
        char rmse[96] = "";
        if (c->rmse_after >= 0)
            std::snprintf(rmse, sizeof rmse, ";  off the reference %.4f (was %.4f)", c->rmse_after, c->rmse_before);
        ImGui::TextDisabled("  costs %.1f ms a sample (was %.1f)%s", c->ms_after, c->ms_before, rmse);
    }
}

/* One parameter's control: its label is the key inside its section. */
void param_control(const panel_model *m, const scene_param *p, size_t section_len, panel_actions *out)
{
    const char *label = p->key + section_len + (p->key[section_len] == '.' ? 1 : 0);
    double v[3] = {p->value[0], p->value[1], p->value[2]};
    bool changed = false;
    ImGui::PushID(p->key);
    switch (p->type) {
    case PARAM_BOOL: {
        bool b = v[0] != 0;
        changed = ImGui::Checkbox(label, &b);
        v[0] = b;
        break;
    }
    case PARAM_ENUM: {
        const char *name = p->names;
        for (int i = 0; i < (int)v[0] && i < p->name_count; i++)
            name += std::strlen(name) + 1;
        if (ImGui::BeginCombo(label, name)) {
            const char *n = p->names;
            for (int i = 0; i < p->name_count; i++, n += std::strlen(n) + 1)
                if (ImGui::Selectable(n, i == (int)v[0]) && i != (int)v[0]) {
                    v[0] = i;
                    changed = true;
                    out->edit_started = true;
                }
            ImGui::EndCombo();
        }
        break;
    }
    case PARAM_COLOR: {
        float c[3] = {(float)v[0], (float)v[1], (float)v[2]};
        changed = ImGui::ColorEdit3(label, c, ImGuiColorEditFlags_Float);
        for (int i = 0; i < 3; i++)
            v[i] = c[i];
        break;
    }
    case PARAM_VEC3:
        if (ends_with(p->key, "direction")) {
            ImGui::TextUnformatted(label);
            changed = direction_control(label, v);
        } else {
            float f[3] = {(float)v[0], (float)v[1], (float)v[2]};
            float big = std::max({std::fabs(f[0]), std::fabs(f[1]), std::fabs(f[2]), 1e-3f});
            changed = ImGui::DragFloat3(label, f, big * 0.005f, (float)p->lo, (float)p->hi, "%.4g",
                                        ImGuiSliderFlags_AlwaysClamp);
            for (int i = 0; i < 3; i++)
                v[i] = f[i];
        }
        break;
    default:
        changed = number_control(label, p, v);
    }
    if (p->type != PARAM_ENUM)
        note_activation(out);
    tooltip(p);
    if (changed)
        edited(m->params, p, v, out);
    cost_line(m, p);
    ImGui::PopID();
}

/* The sections in the order the parser met them (the camera has its own). */
void param_sections(const panel_model *m, panel_actions *out)
{
    std::vector<std::string> order;
    if (m->program_block)
        order.push_back(m->program_block);
    for (int i = 0; i < m->params->count; i++) {
        char s[PARAM_KEY_MAX];
        params_section(m->params->items[i].key, s, sizeof s);
        if (std::strcmp(s, "camera") && std::find(order.begin(), order.end(), s) == order.end())
            order.push_back(s);
    }
    for (const std::string &s : order) {
        std::string title = s;
        title[0] = (char)std::toupper((unsigned char)title[0]);
        ImGuiTreeNodeFlags open = (m->program_block && s == m->program_block) || s == "quality" ? ImGuiTreeNodeFlags_DefaultOpen : 0;
        if (!ImGui::CollapsingHeader(title.c_str(), open))
            continue;
        bool any = false;
        for (int i = 0; i < m->params->count; i++) {
            char sec[PARAM_KEY_MAX];
            params_section(m->params->items[i].key, sec, sizeof sec);
            if (s == sec)
                param_control(m, &m->params->items[i], s.size(), out), any = true;
        }
        if (!any)
            ImGui::TextDisabled("nothing to tune here");
    }
}

void view_section(const panel_model *m, panel_actions *out)
{
    if (!ImGui::CollapsingHeader("Image", ImGuiTreeNodeFlags_DefaultOpen))
        return;
    ImGui::Text("%.1f ms a sample, %.1f fps; %d/%d samples", m->ms_per_sample, m->fps, m->samples, m->spp);
    if (m->internal_width != m->width || m->internal_height != m->height)
        ImGui::Text("moving: %dx%d inside a %dx%d window", m->internal_width, m->internal_height, m->width, m->height);
    else
        ImGui::Text("%dx%d%s", m->width, m->height, m->double_precision ? ", double precision (deep zoom)" : "");
    if (m->cursor_info)
        ImGui::TextUnformatted(m->cursor_info);
    float exposure = m->exposure;
    if (ImGui::SliderFloat("exposure", &exposure, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
        out->exposure_changed = true, out->exposure = exposure;
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("display only: the image keeps its samples");
    int view = m->view;
    if (ImGui::Combo("show", &view, VIEW_NAMES, 3))
        out->view = view;
    if (m->view == 1) {
        float heat = m->heat_max;
        if (ImGui::SliderFloat("heat map top", &heat, 4.0f, 4096.0f, "%.0f steps", ImGuiSliderFlags_Logarithmic))
            out->heat_changed = true, out->heat_max = heat;
    }
    if (ImGui::Button("Grab reference (G)"))
        out->grab_reference = true;
    ImGui::SameLine();
    if (m->reference_rmse >= 0)
        ImGui::Text("RMSE to it %.4f", m->reference_rmse);
    else
        ImGui::TextDisabled("no reference yet");
    ImGui::BeginDisabled(!m->can_undo);
    if (ImGui::Button("Undo (Ctrl+Z)"))
        out->undo = true;
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!m->can_redo);
    if (ImGui::Button("Redo (Ctrl+Y)"))
        out->redo = true;
    ImGui::EndDisabled();
}

void camera_section(const panel_model *m, panel_actions *out)
{
    if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen))
        return;
    for (int i = 0; i < CAMERA_MODE_COUNT; i++) {
        if (i == CAMERA_WALK && !m->can_walk)
            continue;
        if (i)
            ImGui::SameLine();
        if (ImGui::RadioButton(MODE_NAMES[i], m->camera_mode == i))
            out->camera_mode = i;
    }
    if (!ImGui::IsAnyItemActive() || !state.typed_valid) { /* follow the live camera until the user types */
        std::memcpy(state.typed_position, m->position, sizeof state.typed_position);
        std::memcpy(state.typed_look_at, m->look_at, sizeof state.typed_look_at);
        state.typed_fov = m->fov_deg;
        state.typed_valid = true;
    }
    ImGui::InputScalarN("position", ImGuiDataType_Double, state.typed_position, 3, nullptr, nullptr, "%.12g");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("the camera, in metres (a deep zoom needs every digit: type or paste them)");
    ImGui::InputScalarN("look at", ImGuiDataType_Double, state.typed_look_at, 3, nullptr, nullptr, "%.12g");
    ImGui::SliderFloat("fov", &state.typed_fov, 1.0f, 170.0f, "%.1f deg");
    if (ImGui::Button("Go there")) {
        out->camera_typed = true;
        std::memcpy(out->position, state.typed_position, sizeof out->position);
        std::memcpy(out->look_at, state.typed_look_at, sizeof out->look_at);
        out->fov_deg = state.typed_fov;
    }
}

void preset_section(const panel_model *m, panel_actions *out)
{
    if (!ImGui::CollapsingHeader("Presets"))
        return;
    if (!state.preset_named && m->preset_path)
        std::snprintf(state.preset, sizeof state.preset, "%s", m->preset_path);
    if (ImGui::InputText("file", state.preset, sizeof state.preset))
        state.preset_named = true;
    if (ImGui::Button("Save"))
        out->save_preset = true;
    ImGui::SameLine();
    if (ImGui::Button("Load"))
        out->load_preset = true;
    ImGui::SameLine();
    if (ImGui::Button("Copy"))
        out->copy_preset = true;
    ImGui::SameLine();
    if (ImGui::Button("Paste"))
        out->paste_preset = true;
    ImGui::TextDisabled("a preset opens anywhere: fathom --scene FILE");
    std::snprintf(out->preset_path, sizeof out->preset_path, "%s", state.preset);
}

void draw(const panel_model *m, panel_actions *out)
{
    ImGuiIO &io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - PANEL_WIDTH, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(PANEL_WIDTH, io.DisplaySize.y), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.82f);
    ImGui::Begin("fathom", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::TextWrapped("%s", m->scene_title);
    ImGui::PushItemWidth(-110.0f);
    if (m->focus_set_field) /* Enter in the window: type an edit (the panel does not take the keyboard by itself) */
        ImGui::SetKeyboardFocusHere();
    if (ImGui::InputTextWithHint("##set", "Enter, then key=value as --set takes it", state.set, sizeof state.set,
                                 ImGuiInputTextFlags_EnterReturnsTrue)) {
        std::snprintf(out->set, sizeof out->set, "%s", state.set);
        out->edit_started = true;
        state.set[0] = '\0';
    }
    if (m->message && m->message[0])
        ImGui::TextWrapped("%s", m->message);
    view_section(m, out);
    camera_section(m, out);
    param_sections(m, out);
    preset_section(m, out);
    ImGui::PopItemWidth();
    ImGui::End();
}

} // namespace

extern "C" bool panel_init(GLFWwindow *window, err_t *err)
{
    try {
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGuiIO &io = ImGui::GetIO();
        io.IniFilename = nullptr; /* nothing written into the user's folder */
        ImGui::StyleColorsDark();
        if (!ImGui_ImplGlfw_InitForOpenGL(window, true) || !ImGui_ImplOpenGL3_Init("#version 330 core")) {
            ImGui::DestroyContext();
            return err_set(err, "the parameter panel (Dear ImGui) cannot start on this OpenGL");
        }
        state.ready = true;
        return true;
    } catch (const std::exception &e) {
        return err_set(err, "the parameter panel cannot start: %s", e.what());
    }
}

extern "C" void panel_shutdown(void)
{
    if (!state.ready)
        return;
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    state = {};
}

extern "C" void panel_frame(bool shown, const panel_model *m, panel_actions *out)
{
    *out = panel_actions{};
    out->camera_mode = -1;
    out->view = -1;
    if (!state.ready)
        return;
    try {
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        if (shown)
            draw(m, out);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    } catch (const std::exception &) {
        /* a frame without the panel: nothing the user did is lost but this frame's input */
    }
}

extern "C" bool panel_wants_keyboard(void) { return state.ready && ImGui::GetIO().WantCaptureKeyboard; }

extern "C" bool panel_wants_mouse(void) { return state.ready && ImGui::GetIO().WantCaptureMouse; }
