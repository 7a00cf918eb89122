/* A row the test build appends to the command list (tests/firmware/test_command_row.c): an armed
 * echo of a CAPTURE_READ-shaped request, at a code the product leaves free. */
#ifndef COMMAND_ROW_EXTRA_H
#define COMMAND_ROW_EXTRA_H

#define SXL_EXTRA_COMMANDS(X)                                                                      \
    X(TEST_ECHO, 0x7D, test_echo, 1, SXL_CQ, SXL_CQ, "test build only: echoes its request")

#endif /* COMMAND_ROW_EXTRA_H */
