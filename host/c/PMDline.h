/* SPDX-License-Identifier: BSD-2-Clause */
/* The C library's line transport: the chip's serial packets (PMDserial.h) over a serial port or a
   TCP connection (PMDFMU_DEVICE=serial:PATH | tcp:HOST:PORT), to `pmdfmu serve` or a real chip. */
#ifndef PMD_LINE_H
#define PMD_LINE_H

#include <stddef.h>
#include "PMDfmu_types.h"
#include "PMDfmu.h"

typedef struct PMDLine PMDLine;

/* Opens device ("serial:PATH" at baud bit/s, 8N1 raw; or "tcp:HOST:PORT"); address: the chip's
   multi-drop address (0 point-to-point). PMD_ERR_OpeningPort with why filled in on failure. */
PMDresult PMDLineOpen(PMDLine **line, const char *device, PMDuint32 baud, unsigned address, char *why, size_t size);

/* One command: its packet out, the reply in. The chip's status (0, or its host I/O error code),
   or PMD_ERR_NotResponding when no well-formed reply comes even after C-Motion's
   resynchronisation (single zero bytes until a 2-byte reply). */
PMDresult PMDLineCommand(PMDLine *line, PMDuint16 instruction, const PMDuint16 *args, int nargs, PMDuint16 *reply,
                         int nreply);

void PMDLineClose(PMDLine *line);

/* A chip over a line instead of in-process (host/c/PMDfmu.c): the handle's commands go out as
   packets; what needs the FMU itself (PMDFMU_GetInteger, PMDFMU_RunCycles, the dual-port memory)
   answers PMD_ERR_NotSupported with a transport log line; PMDTaskWait and PMDFMU_Wait sleep. */
PMDresult PMDFMU_SetupAxisInterface_Line(PMDAxisHandle *axis_handle, PMDAxis axisNumber, const char *device,
                                         PMDuint32 baud, const PMDFMUOptions *options);
/* The same, every packet carrying address (a multi-drop line's chip address, 0..255) */
PMDresult PMDFMU_SetupAxisInterface_LineAt(PMDAxisHandle *axis_handle, PMDAxis axisNumber, const char *device,
                                           PMDuint32 baud, unsigned address, const PMDFMUOptions *options);

#endif
