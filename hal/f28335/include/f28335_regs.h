/*
 * TMS320F28335 peripheral register frames used by the HAL.
 *
 * Layouts are plain structs of uint16_t (uint32_t for 32-bit registers);
 * every member's WORD offset is checked at compile time against TI's
 * register maps (see f28335_regs_check.c), so a layout slip fails the build
 * on both the target (1 word per uint16_t) and the host (2 bytes per
 * uint16_t). Fields are accessed with the masks below, never with C
 * bit-fields (their layout is compiler-specific).
 *
 * Base addresses live in this file only (F28335_BASE_*). On the target the
 * F28335_* accessors point at those addresses; in a host build
 * (F28335_HOST_REGS) they point at RAM frames in f28335_host_regs that tests
 * can set and inspect.
 */
#ifndef F28335_REGS_H
#define F28335_REGS_H

#include <stdint.h>

#include "f28335_compiler.h"

/* ------------------------------------------------------------------ */
/* Base addresses (data space, word addresses)                         */
/* ------------------------------------------------------------------ */
#define F28335_BASE_FLASH 0x0A80u
#define F28335_BASE_CPUTIMER0 0x0C00u /* timer n at + 8 n */
#define F28335_BASE_PIECTRL 0x0CE0u
#define F28335_BASE_PIEVECT 0x0D00u
#define F28335_BASE_EPWM1 0x6800u /* ePWMn at + 0x40 (n - 1) */
#define F28335_EPWM_STRIDE 0x40u
#define F28335_BASE_EQEP1 0x6B00u
#define F28335_BASE_GPIOCTRL 0x6F80u
#define F28335_BASE_GPIODATA 0x6FC0u
#define F28335_BASE_SYSCTRL 0x7010u
#define F28335_BASE_SCIA 0x7050u
#define F28335_BASE_ADC 0x7100u
#define F28335_ADC_CAL_ADDR 0x380080uL /* factory ADC trim routine in TI OTP */

/* SYSCLKOUT after f28335_clock_init (30 MHz crystal, PLL x10 / 2). */
#define F28335_SYSCLK_HZ ((uint32_t)150000000u)

/* ------------------------------------------------------------------ */
/* ePWM                                                                */
/* ------------------------------------------------------------------ */
typedef struct {
    uint16_t TBCTL;   /* 0x00 */
    uint16_t TBSTS;   /* 0x01 */
    uint16_t TBPHSHR; /* 0x02 */
    uint16_t TBPHS;   /* 0x03 */
    uint16_t TBCTR;   /* 0x04 */
    uint16_t TBPRD;   /* 0x05 */
    uint16_t rsvd1;   /* 0x06 */
    uint16_t CMPCTL;  /* 0x07 */
    uint16_t CMPAHR;  /* 0x08 */
    uint16_t CMPA;    /* 0x09 */
    uint16_t CMPB;    /* 0x0A */
    uint16_t AQCTLA;  /* 0x0B */
    uint16_t AQCTLB;  /* 0x0C */
    uint16_t AQSFRC;  /* 0x0D */
    uint16_t AQCSFRC; /* 0x0E */
    uint16_t DBCTL;   /* 0x0F */
    uint16_t DBRED;   /* 0x10 */
    uint16_t DBFED;   /* 0x11 */
    uint16_t TZSEL;   /* 0x12 */
    uint16_t rsvd2;   /* 0x13 */
    uint16_t TZCTL;   /* 0x14 */
    uint16_t TZEINT;  /* 0x15 */
    uint16_t TZFLG;   /* 0x16 */
    uint16_t TZCLR;   /* 0x17 */
    uint16_t TZFRC;   /* 0x18 */
    uint16_t ETSEL;   /* 0x19 */
    uint16_t ETPS;    /* 0x1A */
    uint16_t ETFLG;   /* 0x1B */
    uint16_t ETCLR;   /* 0x1C */
    uint16_t ETFRC;   /* 0x1D */
    uint16_t PCCTL;   /* 0x1E */
    uint16_t rsvd3;   /* 0x1F */
    uint16_t HRCNFG;  /* 0x20 */
    uint16_t rsvd4;   /* 0x21 */
} f28335_epwm_t;

#define EPWM_TBCTL_CTRMODE_UPDOWN 0x0002u /* CTRMODE 1:0 = 2 */
#define EPWM_TBCTL_CTRMODE_FREEZE 0x0003u
#define EPWM_TBCTL_CTRMODE_MASK 0x0003u
#define EPWM_TBCTL_PHSEN 0x0004u           /* bit 2 */
#define EPWM_TBCTL_PRDLD_IMMEDIATE 0x0008u /* bit 3 (0 = shadow) */
#define EPWM_TBCTL_SYNCOSEL_SHIFT 4u
#define EPWM_TBCTL_SYNCOSEL_MASK 0x0030u
#define EPWM_SYNCOSEL_SYNCI 0u
#define EPWM_SYNCOSEL_CTR_ZERO 1u
#define EPWM_TBCTL_SWFSYNC 0x0040u
#define EPWM_TBCTL_HSPCLKDIV_MASK 0x0380u /* 9:7 */
#define EPWM_TBCTL_CLKDIV_MASK 0x1C00u    /* 12:10 */
#define EPWM_TBCTL_PHSDIR_UP 0x2000u      /* bit 13 */
#define EPWM_TBCTL_FREE_SOFT_SHIFT 14u
#define EPWM_TBCTL_FREE_SOFT_MASK 0xC000u
/* FREE_SOFT on an emulation halt: 0 stop after the next count, 1 stop when the counter completes
 * its cycle (up-down: at CTR = 0), 2 or 3 run free (SPRUG04A, TBCTL). */
#define EPWM_FREE_SOFT_STOP_AT_CYCLE_END 1u

#define EPWM_CMPCTL_LOADAMODE_MASK 0x0003u /* 0 = load at CTR = 0 */
#define EPWM_CMPCTL_LOADBMODE_MASK 0x000Cu
#define EPWM_CMPCTL_SHDWAMODE_IMMEDIATE 0x0010u /* bit 4 (0 = shadow) */
#define EPWM_CMPCTL_SHDWBMODE_IMMEDIATE 0x0040u /* bit 6 */

#define EPWM_AQ_NONE 0u
#define EPWM_AQ_CLEAR 1u
#define EPWM_AQ_SET 2u
#define EPWM_AQ_TOGGLE 3u
#define EPWM_AQ_ZRO_SHIFT 0u
#define EPWM_AQ_PRD_SHIFT 2u
#define EPWM_AQ_CAU_SHIFT 4u
#define EPWM_AQ_CAD_SHIFT 6u
#define EPWM_AQ_CBU_SHIFT 8u
#define EPWM_AQ_CBD_SHIFT 10u
/* AQSFRC: RLDCSF 7:6 (0 = AQCSFRC shadow loaded at CTR = 0). AQCSFRC: CSFA 1:0, CSFB 3:2
 * (0 no force, 1 continuous low, 2 continuous high). */
#define EPWM_AQSFRC_RLDCSF_ZERO 0x0000u
#define EPWM_AQCSFRC_CSFA_LOW 0x0001u
#define EPWM_AQCSFRC_CSFA_HIGH 0x0002u
#define EPWM_AQCSFRC_CSFA_MASK 0x0003u

#define EPWM_DBCTL_OUT_MODE_FULL 0x0003u /* OUT_MODE 1:0 = 3 */
#define EPWM_DBCTL_POLSEL_AHC 0x0008u    /* POLSEL 3:2 = 2: active high complementary */
#define EPWM_DBCTL_IN_MODE_MASK 0x0030u  /* 0: EPWMxA source of both delays */
#define EPWM_DB_MAX_COUNTS 1023u         /* DBRED/DBFED are 10-bit */

#define EPWM_TZSEL_OSHT1 0x0100u   /* bit 8 */
#define EPWM_TZCTL_TZA_LOW 0x0002u /* TZA 1:0 = 2 */
#define EPWM_TZCTL_TZB_LOW 0x0008u /* TZB 3:2 = 2 */
#define EPWM_TZ_INT 0x0001u        /* TZFLG/TZCLR */
#define EPWM_TZ_CBC 0x0002u
#define EPWM_TZ_OST 0x0004u /* TZFLG/TZCLR/TZFRC/TZEINT */

#define EPWM_ETSEL_SOCASEL_SHIFT 8u
#define EPWM_ETSEL_SOCASEL_MASK 0x0700u
#define EPWM_ET_CTR_ZERO 1u
#define EPWM_ETSEL_SOCAEN 0x0800u /* bit 11 */
#define EPWM_ETPS_SOCAPRD_SHIFT 8u
#define EPWM_ETPS_SOCAPRD_MASK 0x0300u

/* ------------------------------------------------------------------ */
/* ADC                                                                 */
/* ------------------------------------------------------------------ */
typedef struct {
    uint16_t ADCTRL1;        /* 0x00 */
    uint16_t ADCTRL2;        /* 0x01 */
    uint16_t ADCMAXCONV;     /* 0x02 */
    uint16_t ADCCHSELSEQ[4]; /* 0x03..0x06 */
    uint16_t ADCASEQSR;      /* 0x07 */
    uint16_t ADCRESULT[16];  /* 0x08..0x17 */
    uint16_t ADCTRL3;        /* 0x18 */
    uint16_t ADCST;          /* 0x19 */
    uint16_t rsvd1[2];       /* 0x1A, 0x1B */
    uint16_t ADCREFSEL;      /* 0x1C */
    uint16_t ADCOFFTRIM;     /* 0x1D */
    uint16_t rsvd2[2];       /* 0x1E, 0x1F */
} f28335_adc_t;

#define ADC_CTRL1_SEQ_CASC 0x0010u /* bit 4 */
#define ADC_CTRL1_CONT_RUN 0x0040u /* bit 6 */
#define ADC_CTRL1_CPS 0x0080u      /* bit 7 */
#define ADC_CTRL1_ACQ_PS_SHIFT 8u
#define ADC_CTRL1_ACQ_PS_MASK 0x0F00u
#define ADC_CTRL1_RESET 0x4000u /* bit 14 */

#define ADC_CTRL2_INT_MOD_SEQ1 0x0400u   /* bit 10 */
#define ADC_CTRL2_INT_ENA_SEQ1 0x0800u   /* bit 11 */
#define ADC_CTRL2_EPWM_SOCA_SEQ1 0x0100u /* bit 8 */
#define ADC_CTRL2_SOC_SEQ1 0x2000u       /* bit 13 */
#define ADC_CTRL2_RST_SEQ1 0x4000u       /* bit 14 */

#define ADC_CTRL3_POWER_UP 0x00E0u /* ADCBGRFDN = 3, ADCPWDN = 1 */
#define ADC_CTRL3_ADCCLKPS_SHIFT 1u
#define ADC_CTRL3_SMODE_SEL 0x0001u

#define ADC_ST_INT_SEQ1 0x0001u
#define ADC_ST_SEQ1_BSY 0x0004u
#define ADC_ST_INT_SEQ1_CLR 0x0010u

/* ------------------------------------------------------------------ */
/* eQEP                                                                */
/* ------------------------------------------------------------------ */
typedef struct {
    uint32_t QPOSCNT;   /* 0x00 */
    uint32_t QPOSINIT;  /* 0x02 */
    uint32_t QPOSMAX;   /* 0x04 */
    uint32_t QPOSCMP;   /* 0x06 */
    uint32_t QPOSILAT;  /* 0x08 */
    uint32_t QPOSSLAT;  /* 0x0A */
    uint32_t QPOSLAT;   /* 0x0C */
    uint32_t QUTMR;     /* 0x0E */
    uint32_t QUPRD;     /* 0x10 */
    uint16_t QWDTMR;    /* 0x12 */
    uint16_t QWDPRD;    /* 0x13 */
    uint16_t QDECCTL;   /* 0x14 */
    uint16_t QEPCTL;    /* 0x15 */
    uint16_t QCAPCTL;   /* 0x16 */
    uint16_t QPOSCTL;   /* 0x17 */
    uint16_t QEINT;     /* 0x18 */
    uint16_t QFLG;      /* 0x19 */
    uint16_t QCLR;      /* 0x1A */
    uint16_t QFRC;      /* 0x1B */
    uint16_t QEPSTS;    /* 0x1C */
    uint16_t QCTMR;     /* 0x1D */
    uint16_t QCPRD;     /* 0x1E */
    uint16_t QCTMRLAT;  /* 0x1F */
    uint16_t QCPRDLAT;  /* 0x20 */
    uint16_t rsvd1[31]; /* 0x21..0x3F */
} f28335_eqep_t;

#define EQEP_QDECCTL_QSRC_QUAD 0x0000u /* QSRC 15:14 = 0 */
#define EQEP_QDECCTL_SWAP 0x0400u      /* bit 10 */

#define EQEP_QEPCTL_WDE 0x0001u
#define EQEP_QEPCTL_UTE 0x0002u
#define EQEP_QEPCTL_QCLM 0x0004u /* latch on unit time-out */
#define EQEP_QEPCTL_QPEN 0x0008u
#define EQEP_QEPCTL_IEL_RISING 0x0010u /* IEL 5:4 = 1 */
#define EQEP_QEPCTL_SWI 0x0080u
#define EQEP_QEPCTL_PCRM_INDEX 0x0000u /* PCRM 13:12 = 0: reset on index */
#define EQEP_QEPCTL_PCRM_MASK 0x3000u
#define EQEP_QEPCTL_FREE_SOFT_FREE 0x8000u /* FREE_SOFT 15:14 = 2 */

#define EQEP_QCAPCTL_UPPS_SHIFT 0u
#define EQEP_QCAPCTL_CCPS_SHIFT 4u
#define EQEP_QCAPCTL_CEN 0x8000u

#define EQEP_INT 0x0001u /* QFLG / QCLR / QEINT bits */
#define EQEP_PCE 0x0002u
#define EQEP_PHE 0x0004u
#define EQEP_QDC 0x0008u
#define EQEP_WTO 0x0010u
#define EQEP_IEL 0x0400u
#define EQEP_UTO 0x0800u

#define EQEP_STS_PCEF 0x0001u
#define EQEP_STS_FIMF 0x0002u
#define EQEP_STS_CDEF 0x0004u
#define EQEP_STS_COEF 0x0008u
#define EQEP_STS_QDF 0x0020u  /* 1 = counting up */
#define EQEP_STS_FIDF 0x0040u /* direction at the first index: 1 = counting up */
#define EQEP_STS_UPEVNT 0x0080u

/* ------------------------------------------------------------------ */
/* PIE, CPU timers                                                     */
/* ------------------------------------------------------------------ */
typedef struct {
    uint16_t PIECTRL; /* 0x00 */
    uint16_t PIEACK;  /* 0x01 */
    struct {
        uint16_t IER; /* 0x02 + 2 (g - 1) */
        uint16_t IFR; /* 0x03 + 2 (g - 1) */
    } group[12];
    uint16_t rsvd1[6]; /* 0x1A..0x1F */
} f28335_piectrl_t;

#define PIE_CTRL_ENPIE 0x0001u

/* Interrupt service routine as stored in the PIE vector table. */
typedef F28335_INTERRUPT void (*f28335_isr_t)(void);

/* 128 entries of 32 bits (on the target: 2 words each). */
typedef struct {
    f28335_isr_t vector[128];
} f28335_pievect_t;

/* Table index of PIE group g (1..12), interrupt k (1..8). */
#define PIE_VECTOR_INDEX(g, k) (32u + 8u * ((g)-1u) + ((k)-1u))
#define PIE_GROUP_ACK(g) ((uint16_t)(1u << ((g)-1u)))
#define CPU_IER_INT1 0x0001u

typedef struct {
    uint32_t TIM;   /* 0x00 counter (counts down) */
    uint32_t PRD;   /* 0x02 period */
    uint16_t TCR;   /* 0x04 control */
    uint16_t rsvd1; /* 0x05 */
    uint16_t TPR;   /* 0x06 prescale low */
    uint16_t TPRH;  /* 0x07 prescale high */
} f28335_cputimer_t;

#define TIMER_TCR_TSS 0x0010u /* bit 4: stop */
#define TIMER_TCR_TRB 0x0020u /* bit 5: reload */
#define TIMER_TCR_SOFT 0x0400u
#define TIMER_TCR_FREE 0x0800u
#define TIMER_TCR_TIE 0x4000u
#define TIMER_TCR_TIF 0x8000u

/* ------------------------------------------------------------------ */
/* System control, flash, GPIO                                         */
/* ------------------------------------------------------------------ */
typedef struct {
    uint16_t rsvd1;    /* 0x00 */
    uint16_t PLLSTS;   /* 0x01 */
    uint16_t rsvd2[8]; /* 0x02..0x09 */
    uint16_t HISPCP;   /* 0x0A */
    uint16_t LOSPCP;   /* 0x0B */
    uint16_t PCLKCR0;  /* 0x0C */
    uint16_t PCLKCR1;  /* 0x0D */
    uint16_t LPMCR0;   /* 0x0E */
    uint16_t rsvd3;    /* 0x0F */
    uint16_t PCLKCR3;  /* 0x10 */
    uint16_t PLLCR;    /* 0x11 */
    uint16_t SCSR;     /* 0x12 */
    uint16_t WDCNTR;   /* 0x13 */
    uint16_t rsvd4;    /* 0x14 */
    uint16_t WDKEY;    /* 0x15 */
    uint16_t rsvd5[3]; /* 0x16..0x18 */
    uint16_t WDCR;     /* 0x19 */
    uint16_t rsvd6[4]; /* 0x1A..0x1D */
    uint16_t MAPCNF;   /* 0x1E */
    uint16_t rsvd7;    /* 0x1F */
} f28335_sysctrl_t;

#define PLLSTS_PLLLOCKS 0x0001u
#define PLLSTS_MCLKSTS 0x0008u
#define PLLSTS_MCLKOFF 0x0040u
#define PLLSTS_DIVSEL_MASK 0x0180u /* 8:7 */
#define PLLSTS_DIVSEL_DIV2 0x0100u /* DIVSEL = 2: CLKIN / 2 */
#define PLLCR_DIV_MASK 0x000Fu

#define PCLKCR0_TBCLKSYNC 0x0004u
#define PCLKCR0_ADCENCLK 0x0008u
#define PCLKCR0_SCIAENCLK 0x0400u
#define PCLKCR1_EPWM_ALL 0x003Fu
#define PCLKCR1_EQEP1ENCLK 0x4000u
#define PCLKCR3_CPUTIMER0ENCLK 0x0100u
#define PCLKCR3_CPUTIMER1ENCLK 0x0200u
#define PCLKCR3_CPUTIMER2ENCLK 0x0400u
#define PCLKCR3_GPIOINENCLK 0x2000u

/* WDCR: WDCHK (5:3) must be written as 101b on every write. */
#define WDCR_DISABLE 0x0068u      /* WDDIS = 1, WDCHK = 101, WDPS = 0 */
#define WDCR_ENABLE_DIV64 0x002Fu /* WDDIS = 0, WDCHK = 101, WDPS = 7 (/64) */
#define WDKEY_1 0x0055u
#define WDKEY_2 0x00AAu

typedef struct {
    uint16_t FOPT;        /* 0x00 */
    uint16_t rsvd1;       /* 0x01 */
    uint16_t FPWR;        /* 0x02 */
    uint16_t FSTATUS;     /* 0x03 */
    uint16_t FSTDBYWAIT;  /* 0x04 */
    uint16_t FACTIVEWAIT; /* 0x05 */
    uint16_t FBANKWAIT;   /* 0x06 */
    uint16_t FOTPWAIT;    /* 0x07 */
} f28335_flash_t;

#define FOPT_ENPIPE 0x0001u
#define FBANKWAIT_PAGEWAIT_SHIFT 8u

typedef struct {
    uint32_t GPACTRL;     /* 0x00 */
    uint32_t GPAQSEL1;    /* 0x02 GPIO0..15, 2 bits each */
    uint32_t GPAQSEL2;    /* 0x04 GPIO16..31 */
    uint32_t GPAMUX1;     /* 0x06 GPIO0..15, 2 bits each */
    uint32_t GPAMUX2;     /* 0x08 GPIO16..31 */
    uint32_t GPADIR;      /* 0x0A */
    uint32_t GPAPUD;      /* 0x0C 1 = pull-up disabled */
    uint32_t rsvd1;       /* 0x0E */
    uint16_t rsvd2[0x30]; /* 0x10..0x3F: port B and C, unused here */
} f28335_gpioctrl_t;

typedef struct {
    uint32_t GPADAT;      /* 0x00 */
    uint32_t GPASET;      /* 0x02 */
    uint32_t GPACLEAR;    /* 0x04 */
    uint32_t GPATOGGLE;   /* 0x06 */
    uint16_t rsvd1[0x18]; /* 0x08..0x1F: ports B and C */
} f28335_gpiodata_t;

/* ------------------------------------------------------------------ */
/* SCI                                                                 */
/* ------------------------------------------------------------------ */
typedef struct {
    uint16_t SCICCR;   /* 0x00 */
    uint16_t SCICTL1;  /* 0x01 */
    uint16_t SCIHBAUD; /* 0x02 */
    uint16_t SCILBAUD; /* 0x03 */
    uint16_t SCICTL2;  /* 0x04 */
    uint16_t SCIRXST;  /* 0x05 */
    uint16_t SCIRXEMU; /* 0x06 */
    uint16_t SCIRXBUF; /* 0x07 */
    uint16_t rsvd1;    /* 0x08 */
    uint16_t SCITXBUF; /* 0x09 */
    uint16_t SCIFFTX;  /* 0x0A */
    uint16_t SCIFFRX;  /* 0x0B */
    uint16_t SCIFFCT;  /* 0x0C */
    uint16_t rsvd2[2]; /* 0x0D, 0x0E */
    uint16_t SCIPRI;   /* 0x0F */
} f28335_sci_t;

#define SCI_CCR_8N1 0x0007u /* SCICHAR = 7 (8 bits), 1 stop, no parity */
#define SCI_CTL1_RXENA 0x0001u
#define SCI_CTL1_TXENA 0x0002u
#define SCI_CTL1_SWRESET 0x0020u /* 0 = held in reset */
#define SCI_RXST_RXERROR 0x0080u
#define SCI_FFTX_SCIRST 0x8000u
#define SCI_FFTX_SCIFFENA 0x4000u
#define SCI_FFTX_TXFIFORESET 0x2000u
#define SCI_FFTX_TXFFINTCLR 0x0040u
#define SCI_FF_ST_SHIFT 8u
#define SCI_FF_ST_MASK 0x1F00u
#define SCI_FFRX_RXFFOVF 0x8000u
#define SCI_FFRX_RXFFOVRCLR 0x4000u
#define SCI_FFRX_RXFIFORESET 0x2000u
#define SCI_FFRX_RXFFINTCLR 0x0040u
#define SCI_FIFO_DEPTH 16u
#define SCI_PRI_FREE 0x0008u

/* ------------------------------------------------------------------ */
/* Accessors: the one place that says where a frame is.                */
/* ------------------------------------------------------------------ */
#define F28335_EPWM_COUNT 6

#if defined(F28335_HOST_REGS)

typedef struct {
    f28335_sysctrl_t sysctrl;
    f28335_flash_t flash;
    f28335_cputimer_t cputimer[3];
    f28335_piectrl_t piectrl;
    f28335_pievect_t pievect;
    f28335_epwm_t epwm[F28335_EPWM_COUNT];
    f28335_eqep_t eqep1;
    f28335_gpioctrl_t gpioctrl;
    f28335_gpiodata_t gpiodata;
    f28335_adc_t adc;
    f28335_sci_t scia;
    uint32_t adc_cal_calls; /* calls of the factory ADC trim routine */
} f28335_host_regs_t;

extern volatile f28335_host_regs_t f28335_host_regs;

/* Zero every host frame and the host core state (test set-up). */
void f28335_host_regs_reset(void);

/* The EALLOW watch: the EALLOW-protected registers (system control, flash, GPIO control, PIE
 * vectors, each ePWM's trip-zone registers and HRCNFG; ../shared/f28335-facts.md) are
 * snapshotted at every EDIS and compared at the next EALLOW. watch_start snapshots now and
 * zeroes the count (after a test's own presets); violations compares once more and returns
 * how many protected-register changes were made outside EALLOW .. EDIS since then. */
void f28335_host_eallow_watch_start(void);
uint32_t f28335_host_eallow_violations(void);

#define F28335_SYSCTRL (&f28335_host_regs.sysctrl)
#define F28335_FLASH (&f28335_host_regs.flash)
#define F28335_CPUTIMER(n) (&f28335_host_regs.cputimer[(n)])
#define F28335_PIECTRL (&f28335_host_regs.piectrl)
#define F28335_PIEVECT (&f28335_host_regs.pievect)
#define F28335_EPWM(i) (&f28335_host_regs.epwm[(i)]) /* i = 0 for ePWM1 */
#define F28335_EQEP1 (&f28335_host_regs.eqep1)
#define F28335_GPIOCTRL (&f28335_host_regs.gpioctrl)
#define F28335_GPIODATA (&f28335_host_regs.gpiodata)
#define F28335_ADC (&f28335_host_regs.adc)
#define F28335_SCIA (&f28335_host_regs.scia)

/* Host models of the few register side effects tests need:
 * - SCI-A: reading SCIRXBUF pops the next injected byte (RXFFST counts the
 *   injected bytes), writing SCITXBUF appends to a transmit log;
 * - time: every hal_cycles_now() advances CPU timer 1 by
 *   f28335_host_cycles_per_read cycles (0 = time stands still). */
void f28335_host_sci_rx_inject(const uint16_t *bytes, uint16_t n);
uint16_t f28335_host_sci_tx_take(uint16_t *out, uint16_t cap);
void f28335_host_sci_rx_popped(void);
void f28335_host_sci_tx_pushed(void);
extern uint32_t f28335_host_cycles_per_read;
#define F28335_SCI_RX_POPPED() f28335_host_sci_rx_popped()
#define F28335_SCI_TX_PUSHED() f28335_host_sci_tx_pushed()
#define F28335_HOST_TIME_PASSES() (f28335_host_regs.cputimer[1].TIM -= f28335_host_cycles_per_read)

#else /* target: fixed addresses */

#define F28335_SCI_RX_POPPED() ((void)0)
#define F28335_SCI_TX_PUSHED() ((void)0)
#define F28335_HOST_TIME_PASSES() ((void)0)

#define F28335_SYSCTRL F28335_ADDR(volatile f28335_sysctrl_t, F28335_BASE_SYSCTRL)
#define F28335_FLASH F28335_ADDR(volatile f28335_flash_t, F28335_BASE_FLASH)
#define F28335_CPUTIMER(n)                                                                         \
    F28335_ADDR(volatile f28335_cputimer_t, F28335_BASE_CPUTIMER0 + 8u * (uint16_t)(n))
#define F28335_PIECTRL F28335_ADDR(volatile f28335_piectrl_t, F28335_BASE_PIECTRL)
#define F28335_PIEVECT F28335_ADDR(volatile f28335_pievect_t, F28335_BASE_PIEVECT)
#define F28335_EPWM(i)                                                                             \
    F28335_ADDR(volatile f28335_epwm_t, F28335_BASE_EPWM1 + F28335_EPWM_STRIDE * (uint16_t)(i))
#define F28335_EQEP1 F28335_ADDR(volatile f28335_eqep_t, F28335_BASE_EQEP1)
#define F28335_GPIOCTRL F28335_ADDR(volatile f28335_gpioctrl_t, F28335_BASE_GPIOCTRL)
#define F28335_GPIODATA F28335_ADDR(volatile f28335_gpiodata_t, F28335_BASE_GPIODATA)
#define F28335_ADC F28335_ADDR(volatile f28335_adc_t, F28335_BASE_ADC)
#define F28335_SCIA F28335_ADDR(volatile f28335_sci_t, F28335_BASE_SCIA)

#endif

#endif /* F28335_REGS_H */
