/* SPDX-License-Identifier: BSD-2-Clause */
/* The C-Motion library's transport: a chip is an instance of the PMDMotionProcessor FMI 2 FMU,
   loaded with dlopen and driven through its host port (host.word/wordCount/strobe in,
   host.ack/error/replyCount/reply out) and its dual-port memory port (memory.*), the path any
   co-simulation tool takes. Chip time passes as the host talks: each command takes the time its
   transfer takes on the host interface (host/c/PMDhosttime.h), and the chip runs every cycle of
   its time grid that falls due meanwhile, so an unchanged polling loop ends.

   POSIX only (dlopen, pthreads; a .fmu file is unpacked with unzip, whose output goes into the
   log line, never onto the terminal). One thread per chip: threads may open, use and close their
   own chips at the same time; a chip (every handle of it) is used by one thread at a time. */
#ifndef PMD_FMU_H
#define PMD_FMU_H

/* The project's one version (python/pmdfmu/__init__.py; tests/test_version.py checks this copy) */
#define PMDFMU_VERSION "0.1.0"

#include <stdint.h>
#include "PMDfmu_types.h"

#ifdef __cplusplus
extern "C" {
#endif

struct PMDHostInterface;    /* host/c/PMDhosttime.h */

/* A message of the FMU's logger: its category (one of the FMU's, log_categories.csv: "errors",
   "warnings", "events" ...), its FMI status (0 OK .. 4 Fatal) and its text, e.g. a refused
   script's "(script text):2: unknown command 'SetPositon'"; or the transport's own, category
   "transport", status 3 (Error), when a call fails: what failed and why, the FMU's reason quoted
   ("fmi2ExitInitializationMode failed: ... (script text):2: ..."). It runs on the thread of the
   call that made the FMU log. */
typedef void (*PMDFMULogCallback)(void *context, const char *category, int status, const char *message);

/* The log of an opening made without options (PMDFMU_SetOpenOptions not called): the transport's
   lines on stderr, prefixed "pmdfmu: ", and nothing else. */
void PMDFMU_LogTransportToStderr(void *context, const char *category, int status, const char *message);

/* Called after every chip cycle the transport runs (then it steps the FMU one cycle at a time),
   with a handle of the chip (axis 1). It may read the chip's outputs (PMDFMU_GetInteger,
   PMDFMU_GetReal) but send no command, and close no chip (the run that calls it goes on). */
typedef void (*PMDFMUCycleCallback)(void *context, PMDAxisInterface chip);

typedef struct {
    const char *fmu;            /* the FMI 2 FMU: a .fmu file or its unpacked directory; NULL: the
                                   environment's PMDFMU_FMU, else the build tree's (PMD_FMU_DEFAULT) */
    double cycleTime;           /* the FMU parameter cycleTime, s; 0: its default (100 us) */
    PMDint32 memorySize;        /* the FMU parameter memorySize, 32-bit words; 0: its default (16384) */
    int loopback;               /* the FMU parameter loopback: actual position = commanded (default 1) */
    const char *script;         /* the FMU parameter script; NULL: none */
    const char *machine;        /* the FMU parameter machine (docs/machine.md): a machine file's path or
                                   its TOML text; NULL: the environment's PMDFMU_MACHINE, else none */
    PMDFMULogCallback log;      /* NULL: no FMU logging; errors still make a call fail */
    void *logContext;
    const char *const *logCategories;   /* the FMU's categories the log gets, NULL-terminated; an
                                   empty list: the FMU's errors only; NULL: "errors" (the chip's
                                   refusals) and "warnings" (a script's refused commands ...). An
                                   unknown category fails the setup (PMD_ERR_Driver). Read by the
                                   setup only */
    PMDFMUCycleCallback cycle;  /* NULL: none (whole runs of cycles in one doStep) */
    void *cycleContext;
    const struct PMDHostInterface *hostInterface;   /* NULL: the default, parallel16 */
} PMDFMUOptions;

/* PMDFMU_MAX_CYCLES=N in the environment: a program whose chip has run N cycles and is still
   running (a poll for an event that cannot come runs forever, as on a real machine) is ended: the
   library writes one line to stderr naming the command it sent last (what it was polling) and
   exits with this status. */
#define PMDFMU_EXIT_MAX_CYCLES 124

/* The defaults above; a NULL options pointer means the same. */
void PMDFMUOptionsInit(PMDFMUOptions *options);

/* Opens a new chip (FMU instance, initialized at time 0) and sets up axis_handle on its axis
   axisNumber (PMDAxis1 .. PMDAxis4). PMD_ERR_OpeningPort if the FMU cannot be found, unpacked,
   loaded or instantiated; PMD_ERR_Driver if initialization fails (a bad parameter or script: the
   log callback gets the FMU's message, then the transport's line quoting it). The chip belongs
   to the calling thread: its PMDTaskWait advances it. */
PMDresult PMDSetupAxisInterface_FMU(PMDAxisHandle *axis_handle, PMDAxis axisNumber, const PMDFMUOptions *options);

/* A chip over a line instead of in-process (PMDFMU_DEVICE; host/c/PMDline.h): the handle's commands go out as
   packets; what needs the FMU itself (PMDFMU_GetInteger, PMDFMU_RunCycles, the dual-port memory)
   answers PMD_ERR_NotSupported with a transport log line; PMDTaskWait and PMDFMU_Wait sleep. */
PMDresult PMDFMU_SetupAxisInterface_Line(PMDAxisHandle *axis_handle, PMDAxis axisNumber, const char *device,
                                         PMDuint32 baud, const PMDFMUOptions *options);
/* The same, every packet carrying address (a multi-drop line's chip address, 0..255) */
PMDresult PMDFMU_SetupAxisInterface_LineAt(PMDAxisHandle *axis_handle, PMDAxis axisNumber, const char *device,
                                           PMDuint32 baud, unsigned address, const PMDFMUOptions *options);

/* C-Motion's: another axis of the same chip. */
PMDresult PMDCopyAxisInterface(PMDAxisHandle *dest_handle, const PMDAxisHandle *src_handle, PMDAxis axis);

/* Releases the handle; the chip (FMU instance) is freed with its last handle. */
PMDresult PMDCloseAxisInterface(PMDAxisHandle *axis_handle);

/* One command through the host port: the instruction word (opcode | axis << 8, axis 0 for a
   chip-wide command), then args; nreply words come back into reply. The generated calls of
   c-motion.h use it. */
PMDresult PMDFMU_Command(PMDAxisInterface axis_intf, PMDuint8 opcode, int chipWide, const PMDuint16 *args,
                         int nargs, PMDuint16 *reply, int nreply);

/* The dual-port upload (seed 000, 1.3): count 32-bit words at word address offset of the external
   memory, written through the FMU's memory port and bypassing the processor (no chip time passes:
   the host writes the RAM itself). transport is the address of a handle's transport_data. */
PMDresult PMDFMU_WriteDPRAM(void *const *transport, PMDuint32 offset, PMDuint32 count, const PMDuint32 *data);

/* The seed's spelling, PMDPCI_WriteDPRAM(transport, offset, count, data[axis][variable][0]): the
   fourth argument is the first word of the block itself (an lvalue), whose address the PCI
   Developer's Kit call takes; the macro passes it, so the seed's line compiles as printed. */
#define PMDPCI_WriteDPRAM(transport, offset, count, first) \
    PMDFMU_WriteDPRAM((transport), (offset), (count), &(first))

/* Host time passes without a command (a host program's sleep): the chip runs the cycles due. */
PMDresult PMDFMU_Wait(PMDAxisInterface axis_intf, PMDuint32 microseconds);

/* C-Motion's sleep: host time passes for every chip the calling thread opened (and not yet
   closed), each running the cycles due, as PMDFMU_Wait does; other threads' chips do not move, so
   a thread's results do not depend on what other threads do. A chip handed to another thread
   stays its opener's for PMDTaskWait: that thread advances it with PMDFMU_Wait, and the opener
   calls no PMDTaskWait while it does. */
void PMDTaskWait(PMDuint32 milliseconds);

/* Runs the next `cycles` cycles of the chip's grid now (the harness's chip.run); the host clock
   moves to the time of the last of them if it was behind. */
PMDresult PMDFMU_RunCycles(PMDAxisInterface axis_intf, PMDuint32 cycles);

/* The host clock, ns since the chip's time 0. */
PMDresult PMDFMU_GetHostTime(PMDAxisInterface axis_intf, uint64_t *nanoseconds);

/* An FMU variable by its FMI 2 name (variables.csv: "axis1.commandedPosition", "chipTime",
   "host.interrupt"); Integer and Boolean variables through GetInteger, Real through GetReal.
   PMD_ERR_InvalidAddress for an unknown name or the wrong type. */
PMDresult PMDFMU_GetInteger(PMDAxisInterface axis_intf, const char *name, PMDint32 *value);
PMDresult PMDFMU_GetReal(PMDAxisInterface axis_intf, const char *name, double *value);

/* Two's complement readings of reply words (no implementation-defined conversion). */
static inline PMDint32 PMDFMU_Int32(PMDuint32 x)
{
    return x < 0x80000000u ? (PMDint32)x : (PMDint32)(x - 0x80000000u) - 0x7FFFFFFF - 1;
}
static inline PMDint16 PMDFMU_Int16(PMDuint16 x)
{
    return (PMDint16)(x < 0x8000u ? (int)x : (int)x - 0x10000);
}

/* Whether a 32-bit argument's value, held in a long (64 bits on LP64 hosts, as the vendor's
   PMDint32 and PMDuint32), is a 32-bit word's: any int32 or uint32 value, whichever the
   parameter's signedness (a program that writes 0xFFFF0000 for -65536 meant the word). */
static inline int PMDFMU_FitsS32(long long x)
{
    return x >= -2147483647LL - 1 && x <= 4294967295LL;
}
static inline int PMDFMU_FitsU32(unsigned long long x)
{
    /* 0 .. 2^32-1, or a negative int32 as it arrives from a long: -2^31 .. -1 wrapped; shifted by 2^31,
       the two runs are the one 0 .. 2^32 + 2^31 - 1 */
    return x + 0x80000000ull <= 0x17FFFFFFFull;
}

#ifdef __cplusplus
}
#endif

#endif
