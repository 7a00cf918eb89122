/* The stack's high-water mark, see stack_watch.h. */
#include "stack_watch.h"

stack_watch_t drive_stack = {0, 0u, 0u}; /* not measured until a platform paints */

void stack_watch_paint(stack_watch_t *w, volatile uint16_t *base, uint16_t words, uint16_t in_use)
{
    uint16_t k;
    const uint16_t first = (in_use < words) ? in_use : words;
    for (k = first; k < words; k++) {
        base[k] = STACK_WATCH_PATTERN;
    }
    w->base = base;
    w->words = words;
    w->used = first;
}

uint16_t stack_watch_scan(stack_watch_t *w)
{
    uint16_t top = w->words;
    /* down to the old mark only: below it the words are known to be used */
    while (top > w->used && w->base[top - 1u] == STACK_WATCH_PATTERN) {
        top--;
    }
    w->used = top;
    return top;
}
