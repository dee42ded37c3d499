/* SPDX-License-Identifier: BSD-2-Clause */
/* The whole C-Motion API over the twin, both generations: what every header name of PMD's a
   program includes (c-motion.h, C-Motion.h, PMDtypes.h, PMDdevice.h ..., with or without the
   c-motion/ folder; generated one-line files) brings in, so that any subset compiles. */
#ifndef PMD_CMOTION_H
#define PMD_CMOTION_H

#include "PMDfmu_types.h"
#include "PMDconstants.h"   /* generated: constants.csv, cmotion_names.csv, cmotion_errors.csv */
#include "PMDopcodes.h"     /* generated: PMDOP<command> */
#include "PMDfmu.h"
#include "PMDcalls.h"       /* generated: commands.csv, cmotion_calls.csv */
#include "PMDlibrary.h"

#endif
