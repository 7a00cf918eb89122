/*
 * Compile-time checks of the register frame layouts against TI's register
 * maps (word offsets, so they hold on the C28x where sizeof(uint16_t) == 1
 * and on a host where it is 2).
 */
#include <stddef.h>

#include "f28335_regs.h"

#define WORD_OFFSET(type, member) (offsetof(type, member) / sizeof(uint16_t))
#define WORD_SIZE(type) (sizeof(type) / sizeof(uint16_t))
#define CHECK_OFFSET(type, member, off, tag)                                                       \
    F28335_CT_ASSERT(WORD_OFFSET(type, member) == (off), tag)

/* ePWM */
CHECK_OFFSET(f28335_epwm_t, TBCTL, 0x00u, epwm_tbctl);
CHECK_OFFSET(f28335_epwm_t, TBSTS, 0x01u, epwm_tbsts);
CHECK_OFFSET(f28335_epwm_t, TBPHSHR, 0x02u, epwm_tbphshr);
CHECK_OFFSET(f28335_epwm_t, TBPHS, 0x03u, epwm_tbphs);
CHECK_OFFSET(f28335_epwm_t, TBCTR, 0x04u, epwm_tbctr);
CHECK_OFFSET(f28335_epwm_t, TBPRD, 0x05u, epwm_tbprd);
CHECK_OFFSET(f28335_epwm_t, CMPCTL, 0x07u, epwm_cmpctl);
CHECK_OFFSET(f28335_epwm_t, CMPAHR, 0x08u, epwm_cmpahr);
CHECK_OFFSET(f28335_epwm_t, CMPA, 0x09u, epwm_cmpa);
CHECK_OFFSET(f28335_epwm_t, CMPB, 0x0Au, epwm_cmpb);
CHECK_OFFSET(f28335_epwm_t, AQCTLA, 0x0Bu, epwm_aqctla);
CHECK_OFFSET(f28335_epwm_t, AQCTLB, 0x0Cu, epwm_aqctlb);
CHECK_OFFSET(f28335_epwm_t, AQSFRC, 0x0Du, epwm_aqsfrc);
CHECK_OFFSET(f28335_epwm_t, AQCSFRC, 0x0Eu, epwm_aqcsfrc);
CHECK_OFFSET(f28335_epwm_t, DBCTL, 0x0Fu, epwm_dbctl);
CHECK_OFFSET(f28335_epwm_t, DBRED, 0x10u, epwm_dbred);
CHECK_OFFSET(f28335_epwm_t, DBFED, 0x11u, epwm_dbfed);
CHECK_OFFSET(f28335_epwm_t, TZSEL, 0x12u, epwm_tzsel);
CHECK_OFFSET(f28335_epwm_t, TZCTL, 0x14u, epwm_tzctl);
CHECK_OFFSET(f28335_epwm_t, TZEINT, 0x15u, epwm_tzeint);
CHECK_OFFSET(f28335_epwm_t, TZFLG, 0x16u, epwm_tzflg);
CHECK_OFFSET(f28335_epwm_t, TZCLR, 0x17u, epwm_tzclr);
CHECK_OFFSET(f28335_epwm_t, TZFRC, 0x18u, epwm_tzfrc);
CHECK_OFFSET(f28335_epwm_t, ETSEL, 0x19u, epwm_etsel);
CHECK_OFFSET(f28335_epwm_t, ETPS, 0x1Au, epwm_etps);
CHECK_OFFSET(f28335_epwm_t, ETFLG, 0x1Bu, epwm_etflg);
CHECK_OFFSET(f28335_epwm_t, ETCLR, 0x1Cu, epwm_etclr);
CHECK_OFFSET(f28335_epwm_t, ETFRC, 0x1Du, epwm_etfrc);
CHECK_OFFSET(f28335_epwm_t, PCCTL, 0x1Eu, epwm_pcctl);
CHECK_OFFSET(f28335_epwm_t, HRCNFG, 0x20u, epwm_hrcnfg);
F28335_CT_ASSERT(WORD_SIZE(f28335_epwm_t) == 0x22u, epwm_size);
F28335_CT_ASSERT(WORD_SIZE(f28335_epwm_t) <= F28335_EPWM_STRIDE, epwm_stride);

/* ADC */
CHECK_OFFSET(f28335_adc_t, ADCTRL1, 0x00u, adc_ctrl1);
CHECK_OFFSET(f28335_adc_t, ADCTRL2, 0x01u, adc_ctrl2);
CHECK_OFFSET(f28335_adc_t, ADCMAXCONV, 0x02u, adc_maxconv);
CHECK_OFFSET(f28335_adc_t, ADCCHSELSEQ, 0x03u, adc_chselseq1);
CHECK_OFFSET(f28335_adc_t, ADCASEQSR, 0x07u, adc_aseqsr);
CHECK_OFFSET(f28335_adc_t, ADCRESULT, 0x08u, adc_result0);
CHECK_OFFSET(f28335_adc_t, ADCTRL3, 0x18u, adc_ctrl3);
CHECK_OFFSET(f28335_adc_t, ADCST, 0x19u, adc_st);
CHECK_OFFSET(f28335_adc_t, ADCREFSEL, 0x1Cu, adc_refsel);
CHECK_OFFSET(f28335_adc_t, ADCOFFTRIM, 0x1Du, adc_offtrim);
F28335_CT_ASSERT(WORD_SIZE(f28335_adc_t) == 0x20u, adc_size);

/* eQEP */
CHECK_OFFSET(f28335_eqep_t, QPOSCNT, 0x00u, eqep_qposcnt);
CHECK_OFFSET(f28335_eqep_t, QPOSINIT, 0x02u, eqep_qposinit);
CHECK_OFFSET(f28335_eqep_t, QPOSMAX, 0x04u, eqep_qposmax);
CHECK_OFFSET(f28335_eqep_t, QPOSCMP, 0x06u, eqep_qposcmp);
CHECK_OFFSET(f28335_eqep_t, QPOSILAT, 0x08u, eqep_qposilat);
CHECK_OFFSET(f28335_eqep_t, QPOSSLAT, 0x0Au, eqep_qposslat);
CHECK_OFFSET(f28335_eqep_t, QPOSLAT, 0x0Cu, eqep_qposlat);
CHECK_OFFSET(f28335_eqep_t, QUTMR, 0x0Eu, eqep_qutmr);
CHECK_OFFSET(f28335_eqep_t, QUPRD, 0x10u, eqep_quprd);
CHECK_OFFSET(f28335_eqep_t, QWDTMR, 0x12u, eqep_qwdtmr);
CHECK_OFFSET(f28335_eqep_t, QWDPRD, 0x13u, eqep_qwdprd);
CHECK_OFFSET(f28335_eqep_t, QDECCTL, 0x14u, eqep_qdecctl);
CHECK_OFFSET(f28335_eqep_t, QEPCTL, 0x15u, eqep_qepctl);
CHECK_OFFSET(f28335_eqep_t, QCAPCTL, 0x16u, eqep_qcapctl);
CHECK_OFFSET(f28335_eqep_t, QPOSCTL, 0x17u, eqep_qposctl);
CHECK_OFFSET(f28335_eqep_t, QEINT, 0x18u, eqep_qeint);
CHECK_OFFSET(f28335_eqep_t, QFLG, 0x19u, eqep_qflg);
CHECK_OFFSET(f28335_eqep_t, QCLR, 0x1Au, eqep_qclr);
CHECK_OFFSET(f28335_eqep_t, QFRC, 0x1Bu, eqep_qfrc);
CHECK_OFFSET(f28335_eqep_t, QEPSTS, 0x1Cu, eqep_qepsts);
CHECK_OFFSET(f28335_eqep_t, QCTMR, 0x1Du, eqep_qctmr);
CHECK_OFFSET(f28335_eqep_t, QCPRD, 0x1Eu, eqep_qcprd);
CHECK_OFFSET(f28335_eqep_t, QCTMRLAT, 0x1Fu, eqep_qctmrlat);
CHECK_OFFSET(f28335_eqep_t, QCPRDLAT, 0x20u, eqep_qcprdlat);
F28335_CT_ASSERT(WORD_SIZE(f28335_eqep_t) == 0x40u, eqep_size);

/* PIE and CPU timers */
CHECK_OFFSET(f28335_piectrl_t, PIECTRL, 0x00u, pie_ctrl);
CHECK_OFFSET(f28335_piectrl_t, PIEACK, 0x01u, pie_ack);
CHECK_OFFSET(f28335_piectrl_t, group, 0x02u, pie_ier1);
F28335_CT_ASSERT(offsetof(f28335_piectrl_t, group[1].IER) / sizeof(uint16_t) == 0x04u, pie_ier2);
F28335_CT_ASSERT(offsetof(f28335_piectrl_t, group[0].IFR) / sizeof(uint16_t) == 0x03u, pie_ifr1);
F28335_CT_ASSERT(offsetof(f28335_piectrl_t, group[11].IFR) / sizeof(uint16_t) == 0x19u, pie_ifr12);
F28335_CT_ASSERT(WORD_SIZE(f28335_piectrl_t) == 0x20u, pie_size);
/* Vector of INT1.1 at 0x0D40, INT13 at 0x0D1A (2 words per entry on the target). */
F28335_CT_ASSERT(PIE_VECTOR_INDEX(1u, 1u) * 2u == 0x40u, pie_vect_int1_1);
F28335_CT_ASSERT(PIE_VECTOR_INDEX(5u, 1u) * 2u == 0x80u, pie_vect_int5_1);
#if F28335_TARGET && !defined(F28335_LINK_PROXY) /* 32-bit code pointers: cl2000 only */
F28335_CT_ASSERT(sizeof(f28335_isr_t) == 2u, pie_vect_entry);
F28335_CT_ASSERT(WORD_SIZE(f28335_pievect_t) == 0x100u, pie_vect_size);
#endif

CHECK_OFFSET(f28335_cputimer_t, TIM, 0x00u, timer_tim);
CHECK_OFFSET(f28335_cputimer_t, PRD, 0x02u, timer_prd);
CHECK_OFFSET(f28335_cputimer_t, TCR, 0x04u, timer_tcr);
CHECK_OFFSET(f28335_cputimer_t, TPR, 0x06u, timer_tpr);
CHECK_OFFSET(f28335_cputimer_t, TPRH, 0x07u, timer_tprh);
F28335_CT_ASSERT(WORD_SIZE(f28335_cputimer_t) == 0x08u, timer_size);

/* System control, flash, GPIO */
CHECK_OFFSET(f28335_sysctrl_t, PLLSTS, 0x01u, sys_pllsts);
CHECK_OFFSET(f28335_sysctrl_t, HISPCP, 0x0Au, sys_hispcp);
CHECK_OFFSET(f28335_sysctrl_t, LOSPCP, 0x0Bu, sys_lospcp);
CHECK_OFFSET(f28335_sysctrl_t, PCLKCR0, 0x0Cu, sys_pclkcr0);
CHECK_OFFSET(f28335_sysctrl_t, PCLKCR1, 0x0Du, sys_pclkcr1);
CHECK_OFFSET(f28335_sysctrl_t, PCLKCR3, 0x10u, sys_pclkcr3);
CHECK_OFFSET(f28335_sysctrl_t, PLLCR, 0x11u, sys_pllcr);
CHECK_OFFSET(f28335_sysctrl_t, SCSR, 0x12u, sys_scsr);
CHECK_OFFSET(f28335_sysctrl_t, WDCNTR, 0x13u, sys_wdcntr);
CHECK_OFFSET(f28335_sysctrl_t, WDKEY, 0x15u, sys_wdkey);
CHECK_OFFSET(f28335_sysctrl_t, WDCR, 0x19u, sys_wdcr);
F28335_CT_ASSERT(WORD_SIZE(f28335_sysctrl_t) == 0x20u, sys_size);

CHECK_OFFSET(f28335_flash_t, FOPT, 0x00u, flash_fopt);
CHECK_OFFSET(f28335_flash_t, FPWR, 0x02u, flash_fpwr);
CHECK_OFFSET(f28335_flash_t, FSTDBYWAIT, 0x04u, flash_fstdbywait);
CHECK_OFFSET(f28335_flash_t, FACTIVEWAIT, 0x05u, flash_factivewait);
CHECK_OFFSET(f28335_flash_t, FBANKWAIT, 0x06u, flash_fbankwait);
CHECK_OFFSET(f28335_flash_t, FOTPWAIT, 0x07u, flash_fotpwait);

CHECK_OFFSET(f28335_gpioctrl_t, GPAQSEL1, 0x02u, gpio_qsel1);
CHECK_OFFSET(f28335_gpioctrl_t, GPAQSEL2, 0x04u, gpio_qsel2);
CHECK_OFFSET(f28335_gpioctrl_t, GPAMUX1, 0x06u, gpio_mux1);
CHECK_OFFSET(f28335_gpioctrl_t, GPAMUX2, 0x08u, gpio_mux2);
CHECK_OFFSET(f28335_gpioctrl_t, GPADIR, 0x0Au, gpio_dir);
CHECK_OFFSET(f28335_gpioctrl_t, GPAPUD, 0x0Cu, gpio_pud);
F28335_CT_ASSERT(WORD_SIZE(f28335_gpioctrl_t) == 0x40u, gpioctrl_size);
CHECK_OFFSET(f28335_gpiodata_t, GPADAT, 0x00u, gpio_dat);
CHECK_OFFSET(f28335_gpiodata_t, GPASET, 0x02u, gpio_set);
CHECK_OFFSET(f28335_gpiodata_t, GPACLEAR, 0x04u, gpio_clear);
CHECK_OFFSET(f28335_gpiodata_t, GPATOGGLE, 0x06u, gpio_toggle);
F28335_CT_ASSERT(WORD_SIZE(f28335_gpiodata_t) == 0x20u, gpiodata_size);

/* SCI */
CHECK_OFFSET(f28335_sci_t, SCICCR, 0x00u, sci_ccr);
CHECK_OFFSET(f28335_sci_t, SCICTL1, 0x01u, sci_ctl1);
CHECK_OFFSET(f28335_sci_t, SCIHBAUD, 0x02u, sci_hbaud);
CHECK_OFFSET(f28335_sci_t, SCILBAUD, 0x03u, sci_lbaud);
CHECK_OFFSET(f28335_sci_t, SCICTL2, 0x04u, sci_ctl2);
CHECK_OFFSET(f28335_sci_t, SCIRXST, 0x05u, sci_rxst);
CHECK_OFFSET(f28335_sci_t, SCIRXBUF, 0x07u, sci_rxbuf);
CHECK_OFFSET(f28335_sci_t, SCITXBUF, 0x09u, sci_txbuf);
CHECK_OFFSET(f28335_sci_t, SCIFFTX, 0x0Au, sci_fftx);
CHECK_OFFSET(f28335_sci_t, SCIFFRX, 0x0Bu, sci_ffrx);
CHECK_OFFSET(f28335_sci_t, SCIFFCT, 0x0Cu, sci_ffct);
CHECK_OFFSET(f28335_sci_t, SCIPRI, 0x0Fu, sci_pri);
F28335_CT_ASSERT(WORD_SIZE(f28335_sci_t) == 0x10u, sci_size);

/* Base addresses against the data-space map. */
F28335_CT_ASSERT(F28335_BASE_EPWM1 + 5u * F28335_EPWM_STRIDE == 0x6940u, epwm6_base);
F28335_CT_ASSERT(F28335_BASE_PIEVECT - F28335_BASE_PIECTRL == 0x20u, pie_bases);

/* A translation unit must declare something ISO C accepts as non-empty. */
int f28335_regs_check_anchor(void);
int f28335_regs_check_anchor(void) { return 0; }
