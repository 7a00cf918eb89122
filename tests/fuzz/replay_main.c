/* Runs the fuzz target over files (the committed corpus) without libFuzzer, so every build
 * and compiler exercises the harness as a regression test. usage: replay FILE... */
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);

int main(int argc, char **argv)
{
    static unsigned char buf[1 << 20];
    int i;
    if (argc < 2) {
        fprintf(stderr, "replay: no input files (usage: replay FILE...)\n");
        return 2;
    }
    for (i = 1; i < argc; i++) {
        FILE *f = fopen(argv[i], "rb");
        size_t n;
        if (!f) {
            fprintf(stderr, "replay: cannot open '%s'\n", argv[i]);
            return 1;
        }
        n = fread(buf, 1, sizeof buf, f);
        fclose(f);
        (void)LLVMFuzzerTestOneInput(buf, n);
    }
    printf("replay: %d inputs, no invariant violated\n", argc - 1);
    return 0;
}
