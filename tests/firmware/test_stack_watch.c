/* The stack's paint and high-water mark (firmware/app/measure/stack_watch.c) on a word array
 * standing for the C28x stack, which grows upward from its first word. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "measure/stack_watch.h"

#define WORDS 64u

static volatile uint16_t region[WORDS];

/* The words below in_use hold what the running code left there: the paint leaves them. */
static void fill(uint16_t value)
{
    uint16_t k;
    for (k = 0u; k < WORDS; k++) {
        region[k] = value;
    }
}

static void test_paint_skips_the_part_in_use(void **state)
{
    stack_watch_t w;
    uint16_t k;
    (void)state;
    fill(0x1234u);
    stack_watch_paint(&w, region, WORDS, 10u);
    for (k = 0u; k < 10u; k++) {
        assert_int_equal(region[k], 0x1234u);
    }
    for (k = 10u; k < WORDS; k++) {
        assert_int_equal(region[k], STACK_WATCH_PATTERN);
    }
    assert_int_equal(w.words, WORDS);
    assert_int_equal(stack_watch_scan(&w), 10u); /* nothing deeper yet: what was in use */
}

static void test_mark_is_the_highest_word_written(void **state)
{
    stack_watch_t w;
    (void)state;
    fill(0u);
    stack_watch_paint(&w, region, WORDS, 4u);
    region[20] = 0u;                  /* a frame up to word 20 ... */
    region[30] = 7u;                  /* ... and one reaching word 30 */
    region[25] = STACK_WATCH_PATTERN; /* words between left unwritten: no gap hides 30 */
    assert_int_equal(stack_watch_scan(&w), 31u);
    region[12] = 1u; /* shallower use later: the mark stays */
    assert_int_equal(stack_watch_scan(&w), 31u);
    region[40] = 1u; /* deeper: it rises */
    assert_int_equal(stack_watch_scan(&w), 41u);
    assert_int_equal(w.used, 41u);
}

static void test_full_stack_reads_as_all_used(void **state)
{
    stack_watch_t w;
    (void)state;
    fill(0u);
    stack_watch_paint(&w, region, WORDS, 0u);
    assert_int_equal(stack_watch_scan(&w), 0u);
    region[WORDS - 1u] = 0xFFFFu; /* the last word written: overflow is likely */
    assert_int_equal(stack_watch_scan(&w), WORDS);
}

static void test_in_use_beyond_the_region_paints_nothing(void **state)
{
    stack_watch_t w;
    (void)state;
    fill(0x0101u);
    stack_watch_paint(&w, region, WORDS, (uint16_t)(WORDS + 5u));
    assert_int_equal(region[WORDS - 1u], 0x0101u);
    assert_int_equal(stack_watch_scan(&w), WORDS);
}

/* A platform that paints nothing (the virtual board): size 0, mark 0, no read of any word. */
static void test_not_measured_without_a_paint(void **state)
{
    stack_watch_t w = {0, 0u, 0u};
    (void)state;
    assert_int_equal(stack_watch_scan(&w), 0u);
    assert_int_equal(drive_stack.words, 0u);
    assert_int_equal(stack_watch_scan(&drive_stack), 0u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paint_skips_the_part_in_use),
        cmocka_unit_test(test_mark_is_the_highest_word_written),
        cmocka_unit_test(test_full_stack_reads_as_all_used),
        cmocka_unit_test(test_in_use_beyond_the_region_paints_nothing),
        cmocka_unit_test(test_not_measured_without_a_paint),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
