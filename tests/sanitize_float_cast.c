/* Built only by the sanitize preset: a float out of int16_t's range converted to it must
 * stop the program (UBSan's float-cast-overflow, not part of -fsanitize=undefined), so the
 * suite's run under the sanitizers would catch such a conversion in the code it tests. The
 * value comes from the command line so that the compiler cannot fold the cast away. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    const float f = (argc > 1) ? strtof(argv[1], NULL) : 0.0f;
    const int16_t v = (int16_t)(int32_t)(f * 1.0e6f); /* 1e5 * 1e6 is outside int32_t */
    printf("converted %d: the overflow went unnoticed\n", (int)v);
    return 0;
}
