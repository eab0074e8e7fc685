/* framestats — what the window's frames cost (framestats.h). */
#include "window/framestats.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util.h"

void framestats_init(frame_stats *s, int frames)
{
    memset(s, 0, sizeof *s);
    if (frames <= 0)
        return;
    s->cap = frames < FRAMESTATS_MAX ? frames : FRAMESTATS_MAX;
    s->all_ms = util_calloc((size_t)s->cap, sizeof(double), "the frame statistics");
    s->panel_ms = util_calloc((size_t)s->cap, sizeof(double), "the frame statistics");
    s->swap_ms = util_calloc((size_t)s->cap, sizeof(double), "the frame statistics");
    s->moving = util_calloc((size_t)s->cap, sizeof(bool), "the frame statistics");
}

void framestats_free(frame_stats *s)
{
    free(s->all_ms);
    free(s->panel_ms);
    free(s->swap_ms);
    free(s->moving);
    memset(s, 0, sizeof *s);
}

void framestats_note_sample(frame_stats *s, double ms) { s->frame_ms[s->frame_index++ % FRAMESTATS_HISTORY] = ms; }

double framestats_average_ms(const frame_stats *s)
{
    double sum = 0;
    int n = 0;
    for (int i = 0; i < FRAMESTATS_HISTORY; i++)
        if (s->frame_ms[i] > 0)
            sum += s->frame_ms[i], n++;
    return n ? sum / n : 0;
}

void framestats_forget(frame_stats *s) { memset(s->frame_ms, 0, sizeof s->frame_ms); }

void framestats_note_overhead(frame_stats *s, double frame_ms, double sample_ms)
{
    double over = frame_ms - sample_ms;
    s->overhead_ms = s->overhead_ms > 0 ? 0.8 * s->overhead_ms + 0.2 * over : over;
}

bool framestats_recording(const frame_stats *s) { return s->count < s->cap; }

void framestats_note_frame(frame_stats *s, double frame_ms, double panel_ms, double swap_ms, bool moving)
{
    if (s->count >= s->cap)
        return;
    s->panel_ms[s->count] = panel_ms;
    s->swap_ms[s->count] = swap_ms;
    s->all_ms[s->count] = frame_ms;
    s->moving[s->count++] = moving;
}

static int cmp_ms(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of the n values v[i] where pick[i] == want (sorted in place into tmp); 0 when none. */
static double median_of(const double *v, const bool *pick, bool want, int n, double *tmp, int *count)
{
    int k = 0;
    for (int i = 0; i < n; i++)
        if (pick[i] == want)
            tmp[k++] = v[i];
    *count = k;
    qsort(tmp, (size_t)k, sizeof *tmp, cmp_ms);
    return k ? tmp[k / 2] : 0;
}

void framestats_summary(const frame_stats *s, int w, int h, bool panel_open, const char *what)
{
    if (!s->count)
        return;
    double *tmp = util_alloc(sizeof *tmp * (size_t)s->count, "the frame statistics");
    int moving, still;
    double mf = median_of(s->all_ms, s->moving, true, s->count, tmp, &moving);
    double mp = median_of(s->panel_ms, s->moving, true, s->count, tmp, &moving);
    double sf = median_of(s->all_ms, s->moving, false, s->count, tmp, &still);
    double sp = median_of(s->panel_ms, s->moving, false, s->count, tmp, &still);
    double ms = median_of(s->swap_ms, s->moving, true, s->count, tmp, &moving);
    fprintf(stderr, "fathom: %d frames at %dx%d (%s): %d moving, median %.1f ms (%.1f fps), the panel %.2f ms of it, "
                    "the swap %.1f ms; %d still, median %.1f ms, the panel %.2f ms; %s\n",
            s->count, w, h, panel_open ? "panel open" : "panel closed", moving, mf, mf > 0 ? 1000.0 / mf : 0.0, mp, ms,
            still, sf, sp, what);
    free(tmp);
}
