/*
 * The faults on the link: the drive's one list (firmware/app/lists/drive_faults.h), its codes and
 * bit numbers as the wire carries them and the tools name them (sxlink_names.c).
 */
#ifndef SXLINK_FAULTS_H
#define SXLINK_FAULTS_H

#include "lists/drive_faults.h"

#define SXL_FAULT_LIST(X) DRIVE_FAULT_LIST(X)
#define SXL_FAULT_CODE_COUNT DRIVE_FAULT_CODE_COUNT
#define SXL_FAULT_BIT_COUNT DRIVE_FAULT_BIT_COUNT

#endif /* SXLINK_FAULTS_H */
