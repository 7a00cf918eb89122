/*
 * Statistics of the motor identification: a mean kept in blocks. Samples are summed into a
 * block of a fixed length in single precision, as their differences from the first sample
 * (a large common value would otherwise eat the sum's digits); each closed block's mean goes
 * into a running mean and variance (Welford's update) of the block means, so hundreds of
 * thousands of samples lose no precision and the spread of the blocks gives the uncertainty of
 * the mean (its standard error, 1 sigma).
 */
#ifndef IDENT_STATS_H
#define IDENT_STATS_H

#include <stdint.h>

typedef struct {
    float ref;      /* the first sample: the sums hold differences from it */
    float sum;      /* of the open block */
    int32_t n;      /* samples in the open block */
    int32_t length; /* samples per block */
    int32_t blocks; /* closed blocks */
    float mean;     /* of the closed blocks' means */
    float m2;       /* sum of squared deviations of the block means */
} ident_blocks_t;

void ident_blocks_init(ident_blocks_t *b, int32_t length);
void ident_blocks_add(ident_blocks_t *b, float x);
/* One whole block's mean at once (a block the caller computed). */
void ident_blocks_add_block(ident_blocks_t *b, float block_mean);
/* Mean of the closed blocks (0 when none). */
float ident_blocks_mean(const ident_blocks_t *b);
/* Standard error of that mean from the blocks' spread (0 below two blocks). */
float ident_blocks_sigma(const ident_blocks_t *b);

#endif /* IDENT_STATS_H */
