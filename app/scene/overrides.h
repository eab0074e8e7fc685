/* overrides — the "key=value" edits a user makes to a scene after loading it (the panel's controls,
 * the window's knob keys, a typed --set), kept as one list in which a key appears once (a later edit
 * of the same key replaces the earlier), with undo and redo over whole states of the list. The window
 * reloads the scene with the command line's overrides followed by these, so an edit meets exactly
 * the checks --set does, and a preset or a shot records them. Pure C. */
#ifndef FATHOM_OVERRIDES_H
#define FATHOM_OVERRIDES_H

#include <stdbool.h>

enum { OVERRIDES_MAX = 48, OVERRIDE_LEN = 256, OVERRIDES_UNDO = 32 }; /* OVERRIDE_LEN: a shot keeps as long (shot.h) */

typedef struct override_state {
    char sets[OVERRIDES_MAX][OVERRIDE_LEN];
    int count;
} override_state;

typedef struct overrides {
    override_state now;
    override_state undo[OVERRIDES_UNDO], redo[OVERRIDES_UNDO];
    int undo_count, redo_count;
} overrides;

/* Sets "key=value" (replacing the key's earlier value; a value equal to it changes nothing). False
 * when the text is not key=value or the list is full. */
bool overrides_set(overrides *o, const char *kv);
/* The value set for key (NULL: none). */
const char *overrides_get(const overrides *o, const char *key);
/* Makes the current state an undo step (before an edit); the redo steps are dropped. */
void overrides_checkpoint(overrides *o);
/* Back to the state before the last checkpoint (true), or forward again. */
bool overrides_undo(overrides *o);
bool overrides_redo(overrides *o);
/* The current state as --set strings; n gets the count. */
const char *const *overrides_list(const overrides *o, const char **out, int *n);
void overrides_clear(overrides *o);

#endif
