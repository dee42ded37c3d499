/* SPDX-License-Identifier: BSD-2-Clause */
/* C-Motion's library calls that are not chip commands, both generations: opening and closing
   (2.x's PMDSetupAxisInterface_*, 5.x's peripherals, devices and axes), messages, the task
   helpers of PMDsys.h and PMDdiag.h. Declared from the public API (names and signatures are facts
   of the interface: pmd-reference S1, S3; docs/sources.md); implemented in host/c/PMDdevice.c over
   the FMU transport (PMDfmu.h). modelDescription/cmotion_calls.csv lists them for the docs.

   Every opening opens the twin in-process: a new chip (FMU instance) of the FMU the environment's
   PMDFMU_FMU names, else the build tree's, with the options of PMDFMU_SetOpenOptions. The link a
   program names (COM port, IP address, board address) is kept, not used: one unchanged binary
   runs against the twin. PMDFMU_DEVICE=serial:PATH or tcp:HOST:PORT sends the chip's serial
   packets over that line instead (PMDline.h): to `pmdfmu serve` or a real chip (docs/device.md);
   an opening that cannot open the line answers PMD_ERR_OpeningPort with a transport log line. */
#ifndef PMD_LIBRARY_H
#define PMD_LIBRARY_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "PMDfmu_types.h"
#include "PMDfmu.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The C-Motion generation this library speaks (PMDGetCMotionVersion) */
#define CMOTION_MAJOR_VERSION 5
#define CMOTION_MINOR_VERSION 0

/* The options every opening below uses (the FMU, its parameters, the log, a cycle callback, the
   host interface); copied. NULL: the defaults, and the transport's log lines on stderr, prefixed
   "pmdfmu: ", since a program that opens the vendor's way has no log callback of its own. A host
   interface left NULL is the one the opening names: serial for a serial port (at its baud),
   parallel16 for parallel, PCI and PIO, spi for SPI, fixed for CAN, TCP and UDP. */
PMDresult PMDFMU_SetOpenOptions(const PMDFMUOptions *options);

/* ---- C-Motion 2.x/3.x (Navigator): one handle per axis ---- */

PMDresult PMDSetupAxisInterface_Serial(PMDAxisHandle *axis_handle, PMDAxis axis_number, PMDuint8 port_number);
PMDresult PMDSetupAxisInterface_Parallel(PMDAxisHandle *axis_handle, PMDAxis axis_number, PMDuint16 board_address);
PMDresult PMDSetupAxisInterface_PCI(PMDAxisHandle *axis_handle, PMDAxis axis_number, PMDuint8 board_number);
PMDresult PMDSetupAxisInterface_CAN(PMDAxisHandle *axis_handle, PMDAxis axis_number, PMDuint16 baud,
                                    PMDuint8 nodeID);

/* ---- C-Motion 5.x: peripheral -> device -> axis ---- */

/* C-Motion's version: CMOTION_MAJOR_VERSION.CMOTION_MINOR_VERSION */
PMDresult PMDGetCMotionVersion(PMDuint32 *MajorVersion, PMDuint32 *MinorVersion);

/* A peripheral: the link to a device. hDevice NULL: the host's own port; a device: one of its
   ports (a C-Motion Engine's). */
PMDresult PMDDeviceOpenPeriphSerial(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDparam port, PMDparam baud,
                                    PMDparam parity, PMDparam stopbits);
PMDresult PMDDeviceOpenPeriphTCP(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDparam ipv4address,
                                 PMDparam portnum, PMDparam timeout);
PMDresult PMDDeviceOpenPeriphUDP(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDparam ipv4address,
                                 PMDparam portnum);
PMDresult PMDDeviceOpenPeriphPIO(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDuint16 address,
                                 PMDuint8 eventIRQ, PMDparam datasize);
PMDresult PMDDeviceOpenPeriphCAN(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDparam addressTX,
                                 PMDparam addressRX, PMDparam addressEvent);
PMDresult PMDDeviceOpenPeriphSPI(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDuint8 port,
                                 PMDuint8 chipselect, PMDuint8 mode, PMDuint8 datasize, PMDparam bitrate);
PMDresult PMDDeviceOpenPeriphPRP(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDparam channel,
                                 PMDparam bufsize);
PMDresult PMDDeviceOpenPeriphCME(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice);

/* The older spellings */
#define PMDPeriphOpenCOM PMDDeviceOpenPeriphSerial
#define PMDPeriphOpenTCP PMDDeviceOpenPeriphTCP
#define PMDPeriphOpenUDP PMDDeviceOpenPeriphUDP
#define PMDPeriphOpenPIO PMDDeviceOpenPeriphPIO
#define PMDPeriphOpenCAN PMDDeviceOpenPeriphCAN
#define PMDPeriphOpenSPI PMDDeviceOpenPeriphSPI
#define PMDPeriphOpenPRP PMDDeviceOpenPeriphPRP
#define PMDPeriphOpenCME PMDDeviceOpenPeriphCME

/* A device over the peripheral: a motion processor (MP) or a resource-protocol product (PRP) whose
   motion processor is the twin. Each is a new chip. */
PMDresult PMDPeriphOpenDeviceMP(PMDDeviceHandle *hDevice, PMDPeriphHandle *hPeriph);
PMDresult PMDPeriphOpenDevicePRP(PMDDeviceHandle *hDevice, PMDPeriphHandle *hPeriph);
PMDresult PMDDeviceClose(PMDDeviceHandle *hDevice);
PMDresult PMDDeviceReset(PMDDeviceHandle *hDevice);
PMDresult PMDDeviceNoOperation(PMDDeviceHandle *hDevice);
/* The chip's firmware version (GetVersion): major and minor */
PMDresult PMDDeviceGetVersion(PMDDeviceHandle *hDevice, PMDuint32 *major, PMDuint32 *minor);

/* An axis of a device; hDevice NULL in C-Motion Engine user code: the engine's own device, here
   a chip opened on first use and closed when the user task returns (USER_CODE_TASK). */
PMDresult PMDAxisOpen(PMDAxisHandle *hAxis, PMDDeviceHandle *hDevice, PMDAxis axis_number);
PMDresult PMDAxisClose(PMDAxisHandle *hAxis);

PMDresult PMDPeriphClose(PMDPeriphHandle *hPeriph);
PMDresult PMDPeriphFlush(PMDPeriphHandle *hPeriph);
/* The twin has no user peripherals: these answer PMD_ERR_NotSupported. */
PMDresult PMDPeriphSend(PMDPeriphHandle *hPeriph, const void *data, PMDparam nCount, PMDparam timeoutms);
PMDresult PMDPeriphReceive(PMDPeriphHandle *hPeriph, void *data, PMDparam *pnReceived, PMDparam nExpected,
                           PMDparam timeoutms);
PMDresult PMDPeriphRead(PMDPeriphHandle *hPeriph, void *data, PMDparam offset, PMDparam length);
PMDresult PMDPeriphWrite(PMDPeriphHandle *hPeriph, void *data, PMDparam offset, PMDparam length);

/* The external memory as 32-bit words: writes go through the FMU's memory port (the seed's
   dual-port upload); the port cannot be read (PMD_ERR_NotSupported). */
PMDresult PMDWriteDPRAM(PMDAxisInterface axis_intf, PMDuint32 *data, PMDuint32 offset_in_dwords,
                        PMDuint32 dwords_to_write);
PMDresult PMDReadDPRAM(PMDAxisInterface axis_intf, PMDuint32 *data, PMDuint32 offset_in_dwords,
                       PMDuint32 dwords_to_read);

/* An axis's event, as PMDWaitForEvent and PMDDeviceGetEvent give it */
/* The event's status word is `eventstatus` in today's SDK and `event` in earlier 5.x releases: both
   name it (an anonymous union, a GNU C and C11 feature; elsewhere only `eventstatus`). */
typedef struct tagPMDAxisEvent {
    PMDAxis axis;
#if defined(__GNUC__)
    __extension__ union {
        PMDuint16 eventstatus;
        PMDuint16 event;
    };
#elif defined(__STDC_VERSION__) && __STDC_VERSION__ >= 201112L
    union {
        PMDuint16 eventstatus;
        PMDuint16 event;
    };
#else
    PMDuint16 eventstatus;
#endif
} PMDEvent;

/* A device's memory (PMDDeviceOpenMemory): the external memory (PMDMemoryAddress_DPRAM) as words of
   datasize bytes; only 32-bit writes reach it (the FMU's memory port), anything else is
   PMD_ERR_NotSupported. */
typedef struct tagPMDMemoryHandle {
    PMDDeviceHandle *hDevice;
    PMDparam datasize;
    PMDparam memorytype;
} PMDMemoryHandle;

PMDresult PMDDeviceOpenMemory(PMDMemoryHandle *hMemory, PMDDeviceHandle *hDevice, PMDparam datasize,
                              PMDparam memorytype);
PMDresult PMDMemoryRead(PMDMemoryHandle *hMemory, void *data, PMDuint32 offset, PMDuint32 length);
PMDresult PMDMemoryWrite(PMDMemoryHandle *hMemory, void *data, PMDuint32 offset, PMDuint32 length);
PMDresult PMDMemoryErase(PMDMemoryHandle *hMemory);
PMDresult PMDMemoryClose(PMDMemoryHandle *hMemory);
#define PMDMemoryOpen PMDDeviceOpenMemory

/* A peripheral on a multi-drop line behind another: the same link */
PMDresult PMDPeriphOpenPeriphMultiDrop(PMDPeriphHandle *hPeriph, PMDPeriphHandle *hPeriphParent, PMDparam address);

/* What the twin has no counterpart of (a C-Motion Engine's defaults, user code store, console,
   reset cause and fault codes, events, an Atlas amplifier): PMD_ERR_NotSupported. */
PMDresult PMDDeviceGetDefault(PMDDeviceHandle *hDevice, PMDparam defaultcode, void *value, PMDparam valueSize);
PMDresult PMDDeviceSetDefault(PMDDeviceHandle *hDevice, PMDparam defaultcode, void *value, PMDparam valueSize);
PMDresult PMDDeviceGetInfo(PMDDeviceHandle *hDevice, PMDparam infoID, PMDuint16 option, PMDuint32 *value);
PMDresult PMDDeviceGetResetCause(PMDDeviceHandle *hDevice, PMDuint16 *resetcause, PMDuint16 resetmask);
PMDresult PMDDeviceGetFaultCode(PMDDeviceHandle *hDevice, PMDparam faultID, PMDuint32 *value);
PMDresult PMDDeviceGetEvent(PMDDeviceHandle *hDevice, PMDEvent *eventdata);
PMDresult PMDWaitForEvent(PMDDeviceHandle *hDevice, PMDEvent *eventdata, PMDparam timeout);
PMDresult PMDCMETaskGetState(PMDDeviceHandle *hDevice, PMDTaskState *state);
PMDresult PMDCMETaskStart(PMDDeviceHandle *hDevice, PMDparam taskparam);
PMDresult PMDCMETaskStop(PMDDeviceHandle *hDevice);
PMDresult PMDCMEGetUserCodeVersion(PMDDeviceHandle *hDevice, PMDuint32 *version);
PMDresult PMDCMEGetUserCodeName(PMDDeviceHandle *hDevice, char *name);
PMDresult PMDCMEGetUserCodeDate(PMDDeviceHandle *hDevice, char *date);
/* The same calls under earlier 5.x releases' names (PMD's C-Motion Engine examples of that SDK) */
#define PMDMPDeviceOpen PMDPeriphOpenDeviceMP
#define PMDRPDeviceOpen PMDPeriphOpenDevicePRP
#define PMDPeriphOpenMultiDrop PMDPeriphOpenPeriphMultiDrop
#define PMDTaskGetState PMDCMETaskGetState
#define PMDGetUserCodeFileVersion PMDCMEGetUserCodeVersion
#define PMDGetUserCodeFileName PMDCMEGetUserCodeName
#define PMDGetUserCodeFileDate PMDCMEGetUserCodeDate
PMDresult PMDCMESetConsole(PMDDeviceHandle *hDevice, PMDPeriphHandle *hPeriph);
#define PMDDeviceSetConsole PMDCMESetConsole
PMDresult PMDAtlasAxisOpen(PMDAxisInterface hSourceAxis, PMDAxisInterface hAtlasAxis);

/* PMDutil.h's helpers: polls the event status until a bit of eventmask is set (PMD_ERR_OK) or
   timeoutms of host time pass (PMD_ERR_Timeout); reads dwords_to_read words of a buffer. */
PMDresult WaitForEvent(PMDAxisHandle *phAxis, PMDuint16 eventmask, PMDuint32 timeoutms);
PMDresult ReadBuffer(PMDAxisHandle *phAxis, PMDuint16 bufferID, PMDint32 *pbuffer, PMDuint32 dwords_to_read);
/* No Atlas amplifier is modelled: PMD_ERR_NotSupported */
PMDresult WaitForAtlasToConnect(PMDAxisHandle *phAxis);
/* Sends InitializePhase and returns the chip's answer */
PMDresult InitializePhase(PMDAxisHandle *phAxis);

/* Clears a handle before its opening */
#define PMD_INITIALIZEHANDLE(handle) memset(&handle, 0, sizeof(handle));
#define PMD_IP4_ADDR(o1, o2, o3, o4)                                                                       \
    (((PMDuint32)((o1) & 0xff) << 24) | ((PMDuint32)((o2) & 0xff) << 16) | ((PMDuint32)((o3) & 0xff) << 8) |  \
     (PMDuint32)((o4) & 0xff))
#define PMD_WAITFOREVER ((PMDparam)0xFFFFFFFFUL)
/* PMDRPtypes.h's and PMDintf.h's platform names: the C-Motion Engine's TCP port, the CAN
   identifiers' bases (a node's are base + node ID), and the byte type of older examples */
#define DEFAULT_ETHERNET_PORT 40100
#define CAN_ADDRESS_BASE_RX 0x580
#define CAN_ADDRESS_BASE_TX 0x600
#define CAN_ADDRESS_BASE_INTR 0x180
#ifndef BYTE
#define BYTE PMDuint8
#endif

/* ---- PMDdiag.h ---- */

/* The vendor's text of a result code; "Undefined error occurred" for any other value. */
const char *PMDGetErrorMessage(PMDresult errorCode);
/* A command's name by opcode (Navigator and Magellan), "Unknown opcode" for any other. */
const char *PMDGetOpcodeText(PMDuint16 opCode);

/* The vendor's error helpers: they need a PMDresult named result in scope. */
#define PMD_RESULT(_call)                                                                                  \
    {                                                                                                      \
        result = _call;                                                                                    \
        if (result)                                                                                        \
            PMDprintf("Error: %s, %30s at line: %d in file: %s\n", PMDGetErrorMessage(result), #_call,     \
                      __LINE__, __FILE__);                                                                 \
    }
#define PMD_ABORTONERROR(_call) PMD_RESULT(_call) if (result) PMDTaskAbort(result);

/* ---- PMDsys.h: the host's console and task ---- */

#define PMDprintf printf
#define PMDsprintf sprintf
#define PMDputs puts
#define PMDputch putchar
typedef PMDparam PMDTaskParam;
#define UNUSED(var) ((void)(var));

/* Ends the program with the code (the C-Motion Engine aborts the task). */
void PMDTaskAbort(int UserAbortCode);

/* Host milliseconds since the first call (PMDTaskWait's time: chip time as the host sees it). */
PMDuint32 PMDDeviceGetTickCount(void);

/* A periodic task's wait (the C-Motion Engine's, as FreeRTOS's vTaskDelayUntil): the period after
   *pPreviousTime, which moves on by it. On the twin the wait is PMDTaskWait(increment): chip time
   passes by the period whatever the host's clock did, so a periodic loop polls the chip at its
   period, run after run alike. */
void PMDTaskWaitUntil(PMDuint32 *pPreviousTime, PMDuint32 increment);

/* Runs a C-Motion Engine task on the host: task(0), then closes the engine's device if the task
   opened it (PMDAxisOpen(&hAxis, NULL, axis)); returns the program's exit code. */
int PMDFMU_RunUserTask(void (*task)(PMDTaskParam), const char *name);

#if defined(__GNUC__)
#define PMD_UNUSED_PARAMETER __attribute__((unused))
#else
#define PMD_UNUSED_PARAMETER
#endif

/* C-Motion Engine user code built for the host: the task becomes the program (the vendor's host
   build makes it main); the version is a constant nobody reads. */
#define USER_CODE_TASK(name)                                                                               \
    void name(PMDTaskParam TaskParam);                                                                     \
    int main(void)                                                                                         \
    {                                                                                                      \
        return PMDFMU_RunUserTask(name, #name);                                                            \
    }                                                                                                      \
    void name(PMDTaskParam TaskParam PMD_UNUSED_PARAMETER)
#define USER_CODE_VERSION(major, minor) enum { PMDFMU_USER_CODE_VERSION = ((major) << 16) | (minor) };

#ifdef __cplusplus
}
#endif

#endif
