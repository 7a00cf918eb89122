# CMake toolchain file for TI's C2000 code generation tools (cl2000), target
# TMS320F28335: C28x core with the 32-bit FPU, COFF ABI (the ABI of the
# F2833x header files, libraries and boot ROM examples).
#
#   cmake -S firmware/f28335 -B build/ti \
#         -DCMAKE_TOOLCHAIN_FILE=cmake/ti-c2000-toolchain.cmake \
#         -DTI_CGT_C2000_ROOT=/opt/ti/ti-cgt-c2000_22.6.1.LTS \
#         [-DSIXPHASE_FW_FLOAT=ON]
#   cmake --build build/ti
#
# TI_CGT_C2000_ROOT is the compiler's install directory (the one holding bin/,
# include/, lib/); it may also come from the environment. See docs/porting.md.

set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR c28x)

if(NOT TI_CGT_C2000_ROOT AND DEFINED ENV{TI_CGT_C2000_ROOT})
  set(TI_CGT_C2000_ROOT "$ENV{TI_CGT_C2000_ROOT}")
endif()
if(NOT TI_CGT_C2000_ROOT)
  message(FATAL_ERROR "Set TI_CGT_C2000_ROOT to the C2000 code generation tools directory "
                      "(for example /opt/ti/ti-cgt-c2000_22.6.1.LTS or CCS's tools/compiler/ti-cgt-c2000_*)")
endif()
# Passed on to try_compile projects.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES TI_CGT_C2000_ROOT)

find_program(TI_CL2000 cl2000 PATHS "${TI_CGT_C2000_ROOT}/bin" NO_DEFAULT_PATH REQUIRED)
find_program(TI_AR2000 ar2000 PATHS "${TI_CGT_C2000_ROOT}/bin" NO_DEFAULT_PATH REQUIRED)

set(CMAKE_C_COMPILER "${TI_CL2000}")
set(CMAKE_ASM_COMPILER "${TI_CL2000}")
set(CMAKE_AR "${TI_AR2000}" CACHE FILEPATH "TI archiver")

# No executables can be linked before the linker command file is known.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# Target options, shared by C and assembly:
#   --silicon_version=28     C28x
#   --large_memory_model     -ml, required by the C28x run-time libraries
#   --unified_memory         -mt, program and data share one address space
#   --float_support=fpu32    single-precision FPU of the F28335
#   --abi=coffabi            COFF: 32-bit double, leading underscore on C symbols
set(TI_C2000_TARGET_FLAGS
    "--silicon_version=28 --large_memory_model --unified_memory --float_support=fpu32 --abi=coffabi")

# --gen_func_subsections=on: each function in its own subsection (.text:_name), so the link
# keeps only what is called; what runs from RAM is marked in the sources
# (control/platform/sixphase_placement.h) and collected by F28335_flash.cmd's ramfuncs.
set(CMAKE_C_FLAGS_INIT
    "${TI_C2000_TARGET_FLAGS} --c99 --gen_func_subsections=on --display_error_number --diag_wrap=off --diag_warning=225")
set(CMAKE_ASM_FLAGS_INIT "${TI_C2000_TARGET_FLAGS}")
set(CMAKE_C_FLAGS_RELEASE_INIT "-O2 --opt_for_speed=5")
set(CMAKE_C_FLAGS_DEBUG_INIT "-g -O0")
set(CMAKE_C_FLAGS_RELWITHDEBINFO_INIT "-g -O2 --opt_for_speed=5")

# Linker: ROM autoinitialisation model (.cinit copied by c_int00), the FPU32
# COFF run-time library, stack in M0 + M1 (see the linker command files; 0x700 words, of which
# tools/check_stack_bound.sh requires its bound to leave 20 %).
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "--rom_model --stack_size=0x700 --heap_size=0 --warn_sections --reread_libs \
--search_path=${TI_CGT_C2000_ROOT}/lib --search_path=${TI_CGT_C2000_ROOT}/include")

set(CMAKE_FIND_ROOT_PATH "${TI_CGT_C2000_ROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
