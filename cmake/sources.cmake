# The one list of the firmware's source files, relative to the repository root. The host
# build (top-level CMakeLists.txt), the TI target build (firmware/f28335/CMakeLists.txt),
# the host link check of the target list (tools/ti_link_proxy) and the CCS file list in
# docs/porting.md (checked by tools/check_doc_sources.cmake) all come from here: a file
# added to the firmware is added here once.

get_filename_component(SIXPHASE_REPO_ROOT ${CMAKE_CURRENT_LIST_DIR}/.. ABSOLUTE)

# Portable control core (control/).
set(SIXPHASE_CTL_SOURCES
    control/src/ctl_barrier.c
    control/src/ctl_qmath.c
    control/src/ctl_tables.c
    control/src/ctl_vsd.c
    control/src/ctl_predict.c
    control/src/ctl_speed_pi.c
    control/src/ctl_flux_ref.c
    control/src/ctl_ddc.c
    control/src/ctl_mptc.c
    control/src/ctl_foc.c
    control/src/ctl_foc_config.c
    control/src/ctl_vvmptc.c
    control/src/ctl_protect.c
    control/src/ctl_params.c
    control/src/ctl_config.c
    control/src/ctl_postfault_config.c
    control/src/ctl_postfault.c
    control/src/ctl.c
    control/src/ctl_step.c)

# Commissioning, the motor identification: the drive's side (drive/), the sequence, its steps,
# their excitation and statistics (commission/). The tests build from this list too.
set(SIXPHASE_COMMISSION_SOURCES
    firmware/app/drive/drive_commission.c
    firmware/app/commission/commission.c
    firmware/app/commission/ident_ctx.c
    firmware/app/commission/ident_excite.c
    firmware/app/commission/ident_stats.c
    firmware/app/commission/ident_phase.c
    firmware/app/commission/ident_encoder.c
    firmware/app/commission/ident_resistance.c
    firmware/app/commission/ident_inductance.c
    firmware/app/commission/ident_flux.c
    firmware/app/commission/ident_mech.c
    firmware/app/commission/ident_xy_harmonics.c)

# Drive application (firmware/app, a folder per concept): control ISR body, state machine
# (drive/), capture (capture/), stage profiler and stack watch (measure/), and the
# commissioning above. The drive's tests build from this list with the HAL and core mocked.
set(SIXPHASE_DRIVE_SOURCES
    firmware/app/drive/drive.c
    firmware/app/drive/drive_open_phase.c
    firmware/app/drive/drive_background.c
    firmware/app/drive/drive_capture.c
    firmware/app/capture/capture.c
    firmware/app/measure/profile.c
    firmware/app/measure/stack_watch.c
    ${SIXPHASE_COMMISSION_SOURCES})

# Serial protocol framing shared by the firmware and the host tool.
set(SIXPHASE_SXLINK_SOURCES
    firmware/link/sxlink.c)
# Name tables of the protocol (host tool and simulator only, not linked into the target).
set(SIXPHASE_SXLINK_NAMES_SOURCES
    firmware/link/sxlink_names.c)

# Serial commands of the drive and the background loop's link service (service/).
set(SIXPHASE_DRIVE_LINK_SOURCES
    firmware/app/service/drive_link.c
    firmware/app/service/link_service.c)

# F28335 register-level HAL: the system's part (clock, interrupts, counter, serial port) and the
# power stage's (PWM, ADC, eQEP; a PIL image has the simulator's bus instead).
set(SIXPHASE_HAL_F28335_SYSTEM_SOURCES
    hal/f28335/src/f28335_regs_check.c
    hal/f28335/src/f28335_gpio.c
    hal/f28335/src/f28335_sysctrl.c
    hal/f28335/src/f28335_pie.c
    hal/f28335/src/f28335_cycles.c
    hal/f28335/src/f28335_sci.c)
set(SIXPHASE_HAL_F28335_SOURCES
    ${SIXPHASE_HAL_F28335_SYSTEM_SOURCES}
    hal/f28335/src/f28335_pwm.c
    hal/f28335/src/f28335_adc.c
    hal/f28335/src/f28335_eqep.c)
# Host build only: the register frames as RAM.
set(SIXPHASE_HAL_F28335_HOST_SOURCES
    hal/f28335/src/f28335_host_regs.c)

# F28335 start-up, control interrupt, background loop.
set(SIXPHASE_FW_F28335_SOURCES
    firmware/f28335/fw_ramfuncs.c
    firmware/f28335/fw_startup.c
    firmware/f28335/fw_isr.c
    firmware/f28335/fw_background.c
    firmware/f28335/fw_main.c)
set(SIXPHASE_FW_F28335_ASM_SOURCES
    firmware/f28335/codestart.asm)

# The processor-in-the-loop image (firmware/pil): the drive through the simulator's bridge, the
# simulator's peripheral bus that the host's frames fill, the PIL service; then per platform
# its start-up and the two HAL services of its own (serial port, cycle counter). Built with the
# drive's lists above (docs/profiling.md).
set(SIXPHASE_PIL_SOURCES
    firmware/pil/pil_target.c
    hal/sim/hal_sim.c
    host_sim/bridge/sim_controller_bridge.c
    host_sim/bridge/sim_ctl_wire.c)
# The F28335's PIL image (firmware/f28335/CMakeLists.txt, SIXPHASE_FW_PIL): the PIL sources, the
# register-level HAL but for the peripherals the bus stands in for (PWM, ADC, eQEP), the RAM copy
# and its own main.
set(SIXPHASE_PIL_F28335_SOURCES
    ${SIXPHASE_HAL_F28335_SYSTEM_SOURCES}
    firmware/f28335/fw_ramfuncs.c
    firmware/pil/f28335_pil_main.c)
set(SIXPHASE_PIL_MPS2_SOURCES
    firmware/pil/mps2_main.c
    firmware/pil/mps2_startup.c
    hal/mps2/hal_mps2.c)
set(SIXPHASE_PIL_INCLUDE_DIRS
    firmware/pil
    host_sim
    hal/sim
    hal/mps2)

# Include directories of the drive application: the one root of firmware/app's folders (an
# include names the folder, "drive/drive.h"; firmware/app/README.md) and the protocol's lists
# the application shares (firmware/link). The host libraries and the tests take them from here.
set(SIXPHASE_APP_INCLUDE_DIRS
    firmware/app
    firmware/link)

# Include directories of the target image.
set(SIXPHASE_TARGET_INCLUDE_DIRS
    firmware/f28335
    ${SIXPHASE_APP_INCLUDE_DIRS}
    hal/include
    hal/f28335/include
    hal/f28335/src
    control/include
    control/platform
    control/src)

# Everything the TI image links, C first.
set(SIXPHASE_TARGET_C_SOURCES
    ${SIXPHASE_CTL_SOURCES}
    ${SIXPHASE_DRIVE_SOURCES}
    ${SIXPHASE_DRIVE_LINK_SOURCES}
    ${SIXPHASE_SXLINK_SOURCES}
    ${SIXPHASE_HAL_F28335_SOURCES}
    ${SIXPHASE_FW_F28335_SOURCES})
set(SIXPHASE_TARGET_SOURCES
    ${SIXPHASE_TARGET_C_SOURCES}
    ${SIXPHASE_FW_F28335_ASM_SOURCES})

# sixphase_sources(<out_var> <list_var>...): absolute paths of the named lists.
function(sixphase_sources out)
  set(result)
  foreach(list_var ${ARGN})
    foreach(f ${${list_var}})
      list(APPEND result ${SIXPHASE_REPO_ROOT}/${f})
    endforeach()
  endforeach()
  set(${out} ${result} PARENT_SCOPE)
endfunction()

# sixphase_sources_pick(<out_var> <list_var> <file name>...): absolute paths of the named files of
# one list (a unit test's share of it, by file name); a name the list does not hold stops the
# configuration, so a test cannot build a file the product no longer does.
function(sixphase_sources_pick out list_var)
  set(result)
  foreach(name ${ARGN})
    set(found)
    foreach(f ${${list_var}})
      get_filename_component(base ${f} NAME)
      if(base STREQUAL name)
        set(found ${SIXPHASE_REPO_ROOT}/${f})
      endif()
    endforeach()
    if(NOT found)
      message(FATAL_ERROR "sixphase_sources_pick: ${name} is not in ${list_var} (cmake/sources.cmake)")
    endif()
    list(APPEND result ${found})
  endforeach()
  set(${out} ${result} PARENT_SCOPE)
endfunction()
