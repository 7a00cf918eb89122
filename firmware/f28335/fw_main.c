/* Entry point of the F28335 firmware (c_int00 calls main after C start-up). */
#include "fw.h"

int main(void)
{
    (void)fw_startup();
    for (;;) {
        fw_background_step();
    }
}
