/* Out of line on purpose: see ctl_barrier.h. */
#include "ctl_barrier.h"

void ctl_compiler_barrier(void) {}
