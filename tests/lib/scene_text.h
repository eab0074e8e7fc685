/* scene_text — what the scene tests (scene/test_scene.c, test_scene_edits.c, test_formula.c) share: a
 * scene loaded from text, an error it must give, and how often a text holds another. */
#ifndef FATHOM_TEST_SCENE_TEXT_H
#define FATHOM_TEST_SCENE_TEXT_H

/* Scene files: the shipped scene's content, syntax and value errors, overrides, effect derivation
 * and the CSG → GLSL code generation. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <fcntl.h>
#include <unistd.h>

#include <cmocka.h>

#include "check.h"

#include "scene/overrides.h"
#include "scene/params.h"
#include "scene/formula/formula.h"
#include "scene/scene.h"
#include "view/shot.h"
#include "view/views.h"

/* The scene in `text` (named /tmp/test.json in messages) with n --set overrides. */
bool scene_text_load(const char *text, const char *const *sets, int n, scene *s, err_t *e);

/* `text` with the overrides must fail with an error that mentions `needle`. */
void scene_text_error(const char *text, const char *const *sets, int n, const char *needle);

/* How many times `needle` occurs in `hay` (overlaps counted). */
int scene_text_count(const char *hay, const char *needle);

#endif
