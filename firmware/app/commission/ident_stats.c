/* Block statistics of the motor identification, see ident_stats.h. */
#include "ident_stats.h"

#include "ctl_q.h"
#include "ctl_qmath.h"

void ident_blocks_init(ident_blocks_t *b, int32_t length)
{
    b->ref = 0.0f;
    b->sum = 0.0f;
    b->n = 0;
    b->length = (length > 0) ? length : 1;
    b->blocks = 0;
    b->mean = 0.0f;
    b->m2 = 0.0f;
}

void ident_blocks_add_block(ident_blocks_t *b, float block_mean)
{
    const float delta = block_mean - b->mean;
    b->blocks++;
    b->mean += delta / (float)b->blocks;
    b->m2 += delta * (block_mean - b->mean);
}

void ident_blocks_add(ident_blocks_t *b, float x)
{
    if (b->n == 0 && b->blocks == 0) {
        b->ref = x;
    }
    b->sum += x - b->ref;
    b->n++;
    if (b->n >= b->length) {
        ident_blocks_add_block(b, b->ref + b->sum / (float)b->n);
        b->sum = 0.0f;
        b->n = 0;
    }
}

float ident_blocks_mean(const ident_blocks_t *b) { return b->mean; }

float ident_blocks_sigma(const ident_blocks_t *b)
{
    if (b->blocks < 2) {
        return 0.0f;
    }
    return ctl_sqrtf(b->m2 / ((float)(b->blocks - 1) * (float)b->blocks));
}
