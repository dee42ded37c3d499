/* SPDX-License-Identifier: BSD-2-Clause */
/* C-Motion's basic types and axis handle, as the 2.x API the seed's sample code uses has them
   (pmd-reference S3, the Navigator MC2440 C-Motion; S1 for the handle's transport_data member),
   with fixed-width integers so that PMDuint32 is 32 bits on every host. */
#ifndef PMD_TYPES_H
#define PMD_TYPES_H

#include <stdint.h>

typedef uint8_t PMDuint8;
typedef int8_t PMDint8;
typedef uint16_t PMDuint16;
typedef int16_t PMDint16;
typedef uint32_t PMDuint32;
typedef int32_t PMDint32;

/* A call's result: the chip's host I/O error code (PMD_ERR_OK = 0 .. 0x0F, constants.csv), or one
   of the host-side codes below. */
typedef PMDuint16 PMDresult;

/* An axis number, PMDAxis1 (0) .. PMDAxis4 (3). */
typedef PMDuint16 PMDAxis;

/* One axis of one chip. transport_data is the connection (the FMU instance) it talks through:
   every handle of a chip shares it (PMDCopyAxisInterface). */
typedef struct tagPMDAxisHandle {
    PMDAxis axis;
    void *transport_data;
} PMDAxisHandle;

/* C-Motion's name for what each call takes: &hAxis[n]. */
typedef PMDAxisHandle *PMDAxisInterface;

/* Host-side result codes: the library refused the call before the chip saw it, or the
   transport failed. Names and values as the Magellan C-Motion has them (pmd-reference S1,
   PMDecode.h) [M]; the chip's own codes (0x00-0x0F) are the Error group of constants.csv. */
enum {
    PMD_ERR_InvalidHandle = 0x1106,           /* a NULL handle, or one whose axis field does not fit */
    PMD_ERR_InvalidAddress = 0x1109,          /* a dual-port write outside the external memory */
    PMD_ERR_ParameterOutOfRange = 0x110A,     /* a packed field's value does not fit its bits */
    PMD_ERR_NotResponding = 0x1202,           /* the FMU did not execute the batch, or replied short */
    PMD_ERR_OpeningPort = 0x1205,             /* the FMU could not be found, loaded or instantiated */
    PMD_ERR_InterfaceNotInitialized = 0x1207, /* the handle was never set up */
    PMD_ERR_Driver = 0x1208                   /* an FMI call failed (the log callback has its message) */
};

#endif
