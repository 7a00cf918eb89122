/*
 * The byte stream to a processor-in-the-loop target: a serial port, or the emulated target
 * started here. Raw 8N1, no flow control.
 */
#ifndef PIL_PORT_H
#define PIL_PORT_H

#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

typedef struct {
    int fd;
    pid_t child;          /* the emulator, or 0 */
    int child_fd;         /* the emulator's output, drained while reading (-1: none) */
    char child_said[256]; /* its last words, for an error message */
    int emulated;
    unsigned icount_shift; /* the emulator's -icount: 2^shift ns of virtual time per instruction */
    char path[256];        /* the line's device */
} pil_port_t;

#define PIL_PORT_ICOUNT_SHIFT 6u

/* Opens a target given as "qemu" (the emulated MPS2 AN386, the image of arith: "fixed" or
 * "float") or "serial:PATH[@BAUD]" (default 921600 baud, the F28335 PIL image's). 0, or -1 with a
 * one-line reason. */
int pil_port_open(pil_port_t *p, const char *target, const char *arith, char *err, size_t len);

/* Checks a target's spelling only (the command line's check): 0 or -1 with the reason. */
int pil_port_check_spec(const char *target, char *err, size_t len);

/* Writes every byte; 0, or -1 when the line fails. */
int pil_port_write(pil_port_t *p, const uint16_t *bytes, uint16_t n);

/* Reads what arrives within timeout_ms into buf (at most cap bytes): the count, 0 on timeout, -1
 * when the line fails. */
int pil_port_read(pil_port_t *p, uint8_t *buf, size_t cap, int timeout_ms);

void pil_port_close(pil_port_t *p);

#endif /* PIL_PORT_H */
