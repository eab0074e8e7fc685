/* hud — text lines over the window (stb_easy_font quads), on a translucent panel. GL only. */
#ifndef FATHOM_HUD_H
#define FATHOM_HUD_H

#include <stdbool.h>

#include "util.h"

bool hud_init(err_t *err);
void hud_shutdown(void);
/* Draws `text` (lines split by '\n') at the top-left of a viewport of the given size, scaled by `scale`. */
void hud_draw(const char *text, int width, int height, float scale);

#endif
