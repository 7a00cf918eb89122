/*
 * simavr harness for the AVR build of tools/avr_proxy/replay.c: loads the ELF on an
 * ATmega1284P, answers reads of GPIOR0 with the next input byte, collects writes to GPIOR1 as
 * output, and times the marks written to GPIOR2 (1/2 around ctl_step, 3/4 around
 * ctl_protect_check, 5/6 around ctl_request_params, 0xFF done, 0xFE bad input).
 *
 * usage: avr-proxy-harness ELF INPUT OUTPUT [--max-cycles N] [--stack-floor ADDR] [--mcu NAME]
 * Exit status: 0 done, 1 usage or I/O error, 2 crash, 3 cycle limit, 4 input exhausted,
 * 5 stack reached the floor (the end of .bss: the stack overwrote static data), 6 the program
 * met an unknown input record (mark 0xFE).
 */
#include <errno.h>
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sim_avr.h>
#include <sim_elf.h>
#include <sim_io.h>

#define ADDR_IN 0x3E   /* GPIOR0 (data space) */
#define ADDR_OUT 0x4A  /* GPIOR1 */
#define ADDR_MARK 0x4B /* GPIOR2 */
#define PAINT 0xA5

typedef struct {
    uint64_t n, sum, max, begin;
    int open;
} span_t;

static struct {
    uint8_t *in;
    size_t in_len, in_pos;
    FILE *out;
    uint64_t out_bytes;
    int done;
    int starved;
    int bad_input;
    span_t span[3]; /* step, protect, params */
} h;

static uint8_t read_in(struct avr_t *avr, avr_io_addr_t addr, void *param)
{
    (void)avr;
    (void)addr;
    (void)param;
    if (h.in_pos >= h.in_len) {
        h.starved = 1;
        return 'E';
    }
    return h.in[h.in_pos++];
}

static void write_out(struct avr_t *avr, avr_io_addr_t addr, uint8_t v, void *param)
{
    (void)avr;
    (void)addr;
    (void)param;
    fputc(v, h.out);
    h.out_bytes++;
}

static void write_mark(struct avr_t *avr, avr_io_addr_t addr, uint8_t v, void *param)
{
    (void)addr;
    (void)param;
    if (v == 0xFF || v == 0xFE) {
        h.done = 1;
        h.bad_input = v == 0xFE;
        return;
    }
    if (v >= 1 && v <= 6) {
        span_t *s = &h.span[(v - 1) / 2];
        if (v % 2 == 1) {
            s->begin = avr->cycle;
            s->open = 1;
        } else if (s->open) {
            const uint64_t d = avr->cycle - s->begin;
            s->n++;
            s->sum += d;
            if (d > s->max) {
                s->max = d;
            }
            s->open = 0;
        }
    }
}

static int load_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    long n;
    if (!f) {
        fprintf(stderr, "harness: cannot open %s: %s\n", path, strerror(errno));
        return -1;
    }
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    h.in = malloc((size_t)n + 1);
    if (!h.in || fread(h.in, 1, (size_t)n, f) != (size_t)n) {
        fprintf(stderr, "harness: cannot read %s\n", path);
        fclose(f);
        return -1;
    }
    fclose(f);
    h.in_len = (size_t)n;
    return 0;
}

static void print_span(const char *name, const span_t *s)
{
    printf("%s_calls=%" PRIu64 " %s_cycles_mean=%.0f %s_cycles_max=%" PRIu64 "\n", name, s->n, name,
           s->n ? (double)s->sum / (double)s->n : 0.0, name, s->max);
}

typedef struct {
    const char *mcu;
    uint64_t max_cycles;
    long stack_floor;
} options_t;

/* Options after ELF INPUT OUTPUT; 0 on success. */
static int parse_options(int argc, char **argv, options_t *o)
{
    int i;
    if (argc < 4) {
        fprintf(stderr,
                "usage: %s ELF INPUT OUTPUT [--max-cycles N] [--stack-floor ADDR] "
                "[--mcu NAME]\n",
                argv[0]);
        return -1;
    }
    for (i = 4; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--max-cycles") == 0) {
            o->max_cycles = strtoull(argv[i + 1], NULL, 0);
        } else if (strcmp(argv[i], "--stack-floor") == 0) {
            o->stack_floor = strtol(argv[i + 1], NULL, 0);
        } else if (strcmp(argv[i], "--mcu") == 0) {
            o->mcu = argv[i + 1];
        } else {
            fprintf(stderr, "harness: unknown option %s\n", argv[i]);
            return -1;
        }
    }
    if (i < argc) {
        fprintf(stderr, "harness: option %s needs a value\n", argv[i]);
        return -1;
    }
    return 0;
}

/* The AVR with the firmware loaded, RAM painted and the three ports hooked; NULL on error. */
static avr_t *make_avr(const char *elf, const char *mcu)
{
    static elf_firmware_t fw;
    avr_t *avr;
    if (elf_read_firmware(elf, &fw) != 0) {
        fprintf(stderr, "harness: cannot load ELF %s\n", elf);
        return NULL;
    }
    avr = avr_make_mcu_by_name(mcu);
    if (!avr) {
        fprintf(stderr, "harness: simavr has no core %s\n", mcu);
        return NULL;
    }
    avr_init(avr);
    avr->frequency = 20000000;
    avr->log = LOG_ERROR;
    avr_load_firmware(avr, &fw);
    /* Paint the RAM so the stack's low-water mark can be found afterwards (crt0 initialises
     * .data and .bss on top of it). */
    memset(avr->data + avr->ioend + 1, PAINT, (size_t)(avr->ramend - avr->ioend));
    avr_register_io_read(avr, ADDR_IN, read_in, NULL);
    avr_register_io_write(avr, ADDR_OUT, write_out, NULL);
    avr_register_io_write(avr, ADDR_MARK, write_mark, NULL);
    return avr;
}

/* Runs to the done mark; the exit status (0, or 2 crash, 3 cycle limit, 4 input ran out,
 * 6 unknown record). */
static int run_avr(avr_t *avr, uint64_t max_cycles)
{
    int state = cpu_Running;
    while (!h.done) {
        state = avr_run(avr);
        if (state == cpu_Done || state == cpu_Crashed || avr->cycle > max_cycles) {
            break;
        }
    }
    if (!h.done) {
        if (avr->cycle > max_cycles) {
            fprintf(stderr, "harness: cycle limit %" PRIu64 " reached (pc 0x%x)\n", max_cycles,
                    (unsigned)avr->pc);
            return 3;
        }
        fprintf(stderr, "harness: AVR %s at pc 0x%x after %" PRIu64 " cycles\n",
                state == cpu_Crashed ? "crashed" : "stopped", (unsigned)avr->pc,
                (uint64_t)avr->cycle);
        return 2;
    }
    if (h.starved) {
        fprintf(stderr, "harness: the program read past the end of the input\n");
        return 4;
    }
    if (h.bad_input) {
        fprintf(stderr, "harness: the program met an unknown record tag\n");
        return 6;
    }
    return 0;
}

/* Stack peak from the painted RAM; 5 if the stack reached .bss, else rc. */
static int report_stack(const avr_t *avr, long stack_floor, int rc)
{
    long a = stack_floor;
    if (!(stack_floor > 0 && stack_floor <= avr->ramend)) {
        return rc;
    }
    while (a <= avr->ramend && avr->data[a] == PAINT) {
        a++;
    }
    printf("stack_peak_bytes=%ld free_ram_bytes=%ld\n", (long)avr->ramend - a + 1, a - stack_floor);
    if (a == stack_floor) {
        fprintf(stderr, "harness: the stack reached the end of .bss (0x%lx)\n", stack_floor);
        return (rc == 0) ? 5 : rc;
    }
    return rc;
}

int main(int argc, char **argv)
{
    options_t o = {"atmega1284p", 20000000000ull, -1};
    avr_t *avr;
    int rc;
    if (parse_options(argc, argv, &o) != 0 || load_file(argv[2]) != 0) {
        return 1;
    }
    h.out = fopen(argv[3], "wb");
    if (!h.out) {
        fprintf(stderr, "harness: cannot write %s: %s\n", argv[3], strerror(errno));
        return 1;
    }
    avr = make_avr(argv[1], o.mcu);
    if (!avr) {
        return 1;
    }
    rc = run_avr(avr, o.max_cycles);
    fclose(h.out);
    printf("mcu=%s total_cycles=%" PRIu64 " input_bytes=%zu output_bytes=%" PRIu64 "\n", o.mcu,
           (uint64_t)avr->cycle, h.in_len, h.out_bytes);
    print_span("step", &h.span[0]);
    print_span("protect", &h.span[1]);
    print_span("params", &h.span[2]);
    rc = report_stack(avr, o.stack_floor, rc);
    avr_terminate(avr);
    return rc;
}
