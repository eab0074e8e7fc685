/* panel — see panel.h. Dear ImGui 1.86 (Debian's libimgui-dev) with its GLFW and OpenGL 3 backends. */
#include "window/panel.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
    GLFWwindow *window;
    GLFWkeyfun imgui_key;                     /* the backend's key callback, which ours wraps */
    std::vector<int> pressed, late_release, due_release; /* keys pressed since the last frame; releases held back */
} state;

/* Dear ImGui 1.86 reads keys as held-down flags at each frame: a key pressed and released between two
 * frames (a quick tap while a slow frame renders, or xdotool) would never be seen down. A release that
 * comes before any frame saw its press is handed to ImGui one frame later, before that frame begins
 * (never inside a frame: ImGui checks its modifier keys do not change there). */
void on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    if (action == GLFW_PRESS)
        state.pressed.push_back(key);
    if (action == GLFW_RELEASE && std::find(state.pressed.begin(), state.pressed.end(), key) != state.pressed.end()) {
        state.late_release.push_back(key);
        return;
    }
    state.imgui_key(window, key, scancode, action, mods);
}

/* Turns the control's new value into an override (the window makes the undo step: edit_started). */
void edited(const param_list *l, const scene_param *p, const double v[4], panel_actions *out)
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

void cost_text(const panel_cost *c)
{
    ImGui::TextDisabled("  costs %.1f ms a sample (was %.1f)", c->ms_after, c->ms_before);
    if (c->rmse_after >= 0)
        ImGui::TextDisabled("  RMSE to the reference %.4f (was %.4f)", c->rmse_after, c->rmse_before);
}

void cost_line(const panel_model *m, const scene_param *p)
{
    for (int i = 0; i < m->cost_count; i++)
        if (!std::strcmp(m->costs[i].key, p->key) && m->costs[i].ms_after > 0)
            cost_text(&m->costs[i]);
}

/* One parameter's control: its label is the key inside its section. */
void param_control(const panel_model *m, const scene_param *p, size_t prefix_len, panel_actions *out)
{
    const char *label = p->key + prefix_len + (p->key[prefix_len] == '.' ? 1 : 0);
    double v[4] = {p->value[0], p->value[1], p->value[2], p->value[3]};
    int comps = params_components(p);
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
    case PARAM_COLOR: { /* a fragment's colour with an intensity: the colour, then the intensity's slider */
        float c[3] = {(float)v[0], (float)v[1], (float)v[2]}, width = ImGui::CalcItemWidth();
        if (comps == 4) /* the colour's swatch and fields, then its intensity's slider beside them */
            ImGui::SetNextItemWidth(width * 0.7f);
        changed = ImGui::ColorEdit3(comps == 4 ? "##colour" : label, c, ImGuiColorEditFlags_Float);
        for (int i = 0; i < 3; i++)
            v[i] = c[i];
        if (comps == 4) {
            ImGui::SameLine(0, ImGui::GetStyle().ItemInnerSpacing.x);
            ImGui::SetNextItemWidth(width * 0.3f - ImGui::GetStyle().ItemInnerSpacing.x);
            float w = (float)v[3];
            changed |= ImGui::SliderFloat(label, &w, (float)p->lo, (float)p->hi, "%.3g");
            v[3] = w;
        }
        break;
    }
    case PARAM_VEC3:
        if (ends_with(p->key, "direction")) {
            ImGui::TextUnformatted(label);
            changed = direction_control(label, v);
        } else {
            float f[4] = {(float)v[0], (float)v[1], (float)v[2], (float)v[3]}, big = 1e-3f;
            for (int i = 0; i < comps; i++)
                big = std::max(big, std::fabs(f[i]));
            float lo = (float)p->lo, hi = (float)p->hi;
            changed = ImGui::DragScalarN(label, ImGuiDataType_Float, f, comps, big * 0.005f, &lo, &hi, "%.4g",
                                         ImGuiSliderFlags_AlwaysClamp);
            for (int i = 0; i < comps; i++)
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

/* The array element a key belongs to ("objects.3" for "objects.3.children.0.radius"), or "" when the
 * key after its section is not an element's (the palette's colours stay one list). */
std::string element_of(const char *key, size_t section_len)
{
    const char *rest = key + section_len;
    if (*rest != '.' || !std::isdigit((unsigned char)rest[1]))
        return "";
    size_t n = 1 + std::strspn(rest + 1, "0123456789");
    if (rest[n] != '.')
        return "";
    return std::string(key, section_len + n);
}

/* The element's index (-1: not an element's key), for listing elements in order. */
long element_index(const char *key, size_t section_len)
{
    return element_of(key, section_len).empty() ? -1 : std::strtol(key + section_len + 1, nullptr, 10);
}

/* An element's tree node, titled by what the scene calls it ("3: box (red)"); true when open. */
bool element_node(const param_list *l, const std::string &g, size_t section_len)
{
    const char *label = params_label_of(l, g.c_str());
    std::string title = g.substr(section_len + 1) + (label ? std::string(": ") + label : std::string());
    return ImGui::TreeNode(g.c_str(), "%s", title.c_str());
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
        std::vector<const scene_param *> listed; /* the section's keys, its elements in index order */
        for (int i = 0; i < m->params->count; i++) {
            char sec[PARAM_KEY_MAX];
            params_section(m->params->items[i].key, sec, sizeof sec);
            if (s == sec)
                listed.push_back(&m->params->items[i]);
        }
        std::stable_sort(listed.begin(), listed.end(), [&](const scene_param *a, const scene_param *b) {
            return element_index(a->key, s.size()) < element_index(b->key, s.size());
        });
        bool any = !listed.empty();
        std::string group; /* the element being listed ("objects.3"), its tree node open or not */
        bool group_open = false;
        std::string heading; /* a fragment's #group */
        for (const scene_param *p : listed) {
            if (p->group[0] && heading != p->group) {
                heading = p->group;
                ImGui::Spacing();
                ImGui::TextDisabled("%s", p->group);
                ImGui::Separator();
            }
            std::string g = element_of(p->key, s.size());
            if (g != group) {
                if (group_open)
                    ImGui::TreePop();
                group = g;
                group_open = g.empty() || element_node(m->params, g, s.size());
            }
            if (g.empty())
                param_control(m, p, s.size(), out);
            else if (group_open)
                param_control(m, p, g.size(), out);
        }
        if (group_open && !group.empty())
            ImGui::TreePop();
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
    if (m->unresolved)
    {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 1.0f, 1.0f));
        ImGui::TextWrapped("%s", m->unresolved);
        ImGui::PopStyleColor();
    }
    if (m->cursor_info) /* wrapped: a DEM's line is wider than the panel */
        ImGui::TextWrapped("%s", m->cursor_info);
    float exposure = m->exposure;
    /* a drag field: a slider's grab sat on its own value at 1.00, the middle of the log range */
    if (ImGui::DragFloat("exposure", &exposure, 0.01f, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
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
    if (m->cost_count > 0 && m->costs[m->cost_count - 1].ms_after > 0) { /* the last edit, where it shows */
        ImGui::TextDisabled("last edit: %s", m->costs[m->cost_count - 1].key);
        cost_text(&m->costs[m->cost_count - 1]);
    }
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
        state.window = window;
        state.imgui_key = glfwSetKeyCallback(window, on_key);
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
        for (int key : state.due_release) /* between frames, as GLFW's own events come */
            state.imgui_key(state.window, key, 0, GLFW_RELEASE, 0);
        state.due_release = state.late_release; /* their presses are seen in this frame */
        state.late_release.clear();
        state.pressed.clear();
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
