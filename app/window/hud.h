/* hud — text lines over the window (stb_easy_font quads), on a translucent panel. GL only. */
#ifndef FATHOM_HUD_H
#define FATHOM_HUD_H

#include <stdbool.h>

#include "util.h"

bool hud_init(err_t *err);
void hud_shutdown(void);
/* Draws `text` (lines split by '\n') on a translucent panel whose top-left corner is at (x, y)
 * pixels from the viewport's top-left (a negative y: that far above its bottom), scaled by `scale`. */
void hud_draw(const char *text, float x, float y, int width, int height, float scale);

#endif
