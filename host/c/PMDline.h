/* SPDX-License-Identifier: BSD-2-Clause */
/* The C library's line transport: the chip's serial packets (PMDserial.h) over a serial port or a
   TCP connection (PMDFMU_DEVICE=serial:PATH | tcp:HOST:PORT), to `pmdfmu serve` or a real chip. */
#ifndef PMD_LINE_H
#define PMD_LINE_H

#include <stddef.h>
#include "PMDfmu_types.h"

typedef struct PMDLine PMDLine;

/* The longest reply of the twin's monitor taken (a value, or its reason), terminating zero included */
#define PMD_LINE_MONITOR_REPLY 2048

/* Opens device ("serial:PATH" at baud bit/s, 8N1 raw; or "tcp:HOST:PORT"); address: the chip's
   multi-drop address (0 point-to-point). PMD_ERR_OpeningPort with why filled in on failure. */
PMDresult PMDLineOpen(PMDLine **line, const char *device, PMDuint32 baud, unsigned address, char *why, size_t size);

/* One command: its packet out, the reply in. The chip's status (0, or its host I/O error code),
   or PMD_ERR_NotResponding when no well-formed reply comes even after C-Motion's
   resynchronisation (single zero bytes until a 2-byte reply). */
PMDresult PMDLineCommand(PMDLine *line, PMDuint16 instruction, const PMDuint16 *args, int nargs, PMDuint16 *reply,
                         int nreply);

/* The twin's monitor beside the line (`pmdfmu serve --monitor HOST:PORT`, PMDFMU_MONITOR=tcp:HOST:PORT;
   docs/device.md): what a chip has no packet for (cycles run, host time, FMU variables, the dual-port
   memory), one text request a line. Open connects and selects the line's chip (its address). */
PMDresult PMDLineMonitorOpen(PMDLine *line, const char *monitor, char *why, size_t size);

/* Whether the line has a monitor. */
int PMDLineHasMonitor(const PMDLine *line);

/* One request (without its line feed): PMD_ERR_OK with the value after "ok " in value (empty if none);
   PMD_ERR_Driver with the server's reason in value for an "error" reply; PMD_ERR_NotResponding if
   the monitor went or answered no line. */
PMDresult PMDLineMonitor(PMDLine *line, const char *request, char *value, size_t size);

void PMDLineClose(PMDLine *line);

#endif
