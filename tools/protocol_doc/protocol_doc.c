/*
 * Prints the serial protocol's tables of docs/serial-protocol.md from the lists
 * (firmware/link/sxlink_commands.h, sxlink_payloads.h): `protocol-doc commands` the command
 * table, `protocol-doc NAME` the field table of one payload (ST, FR, PF, CA, CS, CT, CR2, OP,
 * TL). tools/protocol_doc.py writes and checks them there.
 */
#include <stdio.h>
#include <string.h>

#include "sxlink.h"

typedef struct {
    const char *type;
    unsigned bytes, count;
    const char *what;
    unsigned offset;
} field_t;

typedef struct {
    const char *name;
    const field_t *fields;
    unsigned size;
} payload_t;

#define FIELD(name, type, count, what) {#type, SXL_BYTES_##type, (unsigned)(count), what, name},
#define PAYLOAD_FIELDS(prefix)                                                                     \
    static const field_t prefix##_fields[] = {prefix##_FIELDS(FIELD){NULL, 0u, 0u, NULL, 0u}};
SXL_PAYLOAD_LIST(PAYLOAD_FIELDS)
#define PAYLOAD_ROW(prefix) {#prefix, prefix##_fields, (unsigned)prefix##_SIZE},
static const payload_t payloads[] = {SXL_PAYLOAD_LIST(PAYLOAD_ROW)};
#define PAYLOAD_COUNT (sizeof payloads / sizeof payloads[0])

static const payload_t *payload_named(const char *name)
{
    unsigned k;
    for (k = 0u; k < PAYLOAD_COUNT; k++) {
        if (strcmp(payloads[k].name, name) == 0 || strcmp(payloads[k].name + 4, name) == 0) {
            return &payloads[k];
        }
    }
    return NULL;
}

static const char *type_text(const char *type)
{
    static const char *const names[][2] = {
        {"U8", "uint8"}, {"U16", "uint16"}, {"U32", "uint32"}, {"I16", "int16"}, {"I32", "int32"}};
    unsigned k;
    for (k = 0u; k < sizeof names / sizeof names[0]; k++) {
        if (strcmp(names[k][0], type) == 0) {
            return names[k][1];
        }
    }
    return "?";
}

static unsigned field_count(const payload_t *p)
{
    unsigned n = 0u;
    while (p->fields[n].type != NULL) {
        n++;
    }
    return n;
}

static void print_type(const field_t *f)
{
    printf("%s", type_text(f->type));
    if (f->count != 1u) {
        printf(" x %u", f->count);
    }
}

/* A payload in a table cell: none, its fields inline (two at most), or its table's name. */
static void print_cell(const payload_t *p)
{
    const unsigned n = field_count(p);
    unsigned k;
    if (n == 0u) {
        printf("none");
        return;
    }
    if (n > 2u) {
        printf("%u bytes, table `%s` below", p->size, p->name + 4);
        return;
    }
    for (k = 0u; k < n; k++) {
        printf("%s", (k > 0u) ? "; " : "");
        print_type(&p->fields[k]);
        printf(" %s", p->fields[k].what);
    }
}

#define COMMAND_ROW(name, code, handler, armed, request, reply, notes)                             \
    {#name, code, armed, #request, #reply, notes},
typedef struct {
    const char *name;
    unsigned code, armed;
    const char *request, *reply, *notes;
} command_t;
static const command_t commands[] = {SXL_COMMAND_LIST(COMMAND_ROW)
                                         SXL_PLATFORM_COMMAND_LIST(COMMAND_ROW)};

static void print_commands(void)
{
    unsigned k;
    printf("Protocol version %u. Token: the command moves the motor and needs the armed "
           "session's token (4 bytes) in front of its request.\n\n",
           (unsigned)SXL_VERSION);
    printf("| CMD | name | request | reply after the result | token | notes |\n");
    printf("|---|---|---|---|---|---|\n");
    for (k = 0u; k < sizeof commands / sizeof commands[0]; k++) {
        const command_t *c = &commands[k];
        printf("| 0x%02X | %s | ", c->code, c->name);
        print_cell(payload_named(c->request));
        printf(" | ");
        print_cell(payload_named(c->reply));
        printf(" | %s | %s |\n", c->armed ? "yes" : "", c->notes[0] ? c->notes : "-");
    }
}

static void print_fields(const payload_t *p)
{
    const unsigned n = field_count(p);
    unsigned k;
    printf("Table `%s` (`%s_*` in `firmware/link/sxlink_payloads.h`), %u bytes:\n\n", p->name + 4,
           p->name, p->size);
    printf("| offset | type | field |\n|---|---|---|\n");
    for (k = 0u; k < n; k++) {
        printf("| %u | ", p->fields[k].offset);
        print_type(&p->fields[k]);
        printf(" | %s |\n", p->fields[k].what);
    }
}

int main(int argc, char **argv)
{
    const payload_t *p;
    if (argc != 2) {
        fprintf(stderr, "protocol-doc: error: give commands or a payload's name\n");
        return 2;
    }
    if (strcmp(argv[1], "commands") == 0) {
        print_commands();
        return 0;
    }
    p = payload_named(argv[1]);
    if (p == NULL || field_count(p) == 0u) {
        fprintf(stderr, "protocol-doc: error: no payload '%s'\n", argv[1]);
        return 2;
    }
    print_fields(p);
    return 0;
}
