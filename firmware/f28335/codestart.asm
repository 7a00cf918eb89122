; Entry of the F28335 firmware.
;
; The boot ROM jumps to BEGIN: 0x33FFF6 when booting from flash, 0x000000
; when booting to M0 SARAM. Two words are available there: a long branch to
; the code below, which turns the watchdog off (the C start-up initialises
; .ebss/.cinit and could outlast it) and continues at the C run-time's
; _c_int00. main() then runs fw_startup(), which enables the watchdog again
; before the background loop.

WDCR    .set    0x7029              ; SysCtrlRegs.WDCR (0x7010 + 0x19)
WD_OFF  .set    0x0068              ; WDDIS = 1, WDCHK = 101b

        .ref    _c_int00
        .global code_start

        .sect   "codestart"
code_start:
        LB      wd_disable

        .text
wd_disable:
        SETC    OBJMODE             ; C28x object mode
        EALLOW                      ; WDCR is EALLOW-protected
        MOVZ    DP, #WDCR >> 6
        MOV     @WDCR, #WD_OFF
        EDIS
        LB      _c_int00

        .end
