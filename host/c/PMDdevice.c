/* SPDX-License-Identifier: BSD-2-Clause */
/* C-Motion's openings of both generations over the FMU transport (PMDlibrary.h): a program's own
   set-up code, 2.x's PMDSetupAxisInterface_* or 5.x's peripheral -> device -> axis, opens the twin
   in-process, so the program runs unchanged. */
#define _XOPEN_SOURCE 700     /* clock_gettime */
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <time.h>

#include "c-motion.h"
#include "PMDline.h"
#ifdef PMD_HAVE_HOSTTIME
#include "PMDhosttime.h"
#endif

/* The options of PMDFMU_SetOpenOptions, shared by the threads that open chips (under the lock). */
static pthread_mutex_t open_options_lock = PTHREAD_MUTEX_INITIALIZER;
static int open_options_set;
static PMDFMUOptions open_options;
#ifdef PMD_HAVE_HOSTTIME
static PMDHostInterface open_host;
#endif

/* The C-Motion Engine's own device (PMDAxisOpen with no device), opened on first use. */
static pthread_mutex_t engine_lock = PTHREAD_MUTEX_INITIALIZER;
static PMDDeviceHandle engine;
static PMDDeviceHandle *engine_device(PMDDeviceHandle *hDevice, PMDresult *r);

/* No FMU category for the default log: the FMU's errors only (the stderr log keeps the transport's) */
static const char *const no_categories[] = {NULL};

PMDresult PMDFMU_SetOpenOptions(const PMDFMUOptions *options)
{
    pthread_mutex_lock(&open_options_lock);
    open_options_set = options != NULL;
    if (options) {
        open_options = *options;
#ifdef PMD_HAVE_HOSTTIME
        if (options->hostInterface) {
            open_host = *options->hostInterface;
            open_options.hostInterface = &open_host;
        }
#endif
    }
    pthread_mutex_unlock(&open_options_lock);
    return PMD_ERR_OK;
}

static void transport_line(const PMDFMUOptions *options, const char *format, ...)
{
    char text[512];
    va_list ap;
    va_start(ap, format);
    vsnprintf(text, sizeof text, format, ap);
    va_end(ap);
    if (options->log)
        options->log(options->logContext, "transport", 3, text);
}

/* PMDFMU_DEVICE: empty or "fmu" is the twin in-process (NULL); "serial:PATH" and "tcp:HOST:PORT" are
   the chip's serial packets over a line (PMDline.h): the device's text. Anything else: NULL and
   *refused set. */
static const char *device_link(const PMDFMUOptions *options, int *refused)
{
    const char *device = getenv("PMDFMU_DEVICE");
    const char *colon;
    *refused = 0;
    if (!device || !*device || strcmp(device, "fmu") == 0)
        return NULL;
    if (strncmp(device, "serial:", 7) == 0 && device[7])
        return device;
    colon = strncmp(device, "tcp:", 4) == 0 ? strrchr(device + 4, ':') : NULL;
    if (colon && colon > device + 4 && colon[1])
        return device;
    transport_line(options, "PMDFMU_DEVICE=%s: expected serial:PATH or tcp:HOST:PORT (or fmu, or nothing, "
                   "for the twin in-process)", device);
    *refused = 1;
    return NULL;
}

/* The baud rates of C-Motion 5.x's PMDSerialBaud codes (cmotion_names.csv: the names carry them) */
static const PMDuint32 serial_baud[] = {1200, 2400, 9600, 19200, 57600, 115200, 230400, 460800,
                                        921600, 1000000, 2000000, 2500000, 3333333, 5000000, 10000000};

/* Opens a new chip with the handle on axis, the host interface named `host` (a kind of
   host_interfaces.csv) unless the open options give one; baud: a serial line's, 0 for the
   table's default; address: the chip's on a multi-drop line (PMDFMU_DEVICE's links only). */
static PMDresult open_twin_at(PMDAxisHandle *handle, PMDAxis axis, const char *host, PMDuint32 baud,
                              unsigned address)
{
    PMDFMUOptions options;
#ifdef PMD_HAVE_HOSTTIME
    PMDHostInterface interface;
#endif
    const char *device;
    int refused;
    if (!handle)
        return PMD_ERR_InvalidHandle;
    handle->axis = axis;
    handle->transport_data = NULL;
    pthread_mutex_lock(&open_options_lock);
    if (open_options_set) {
        options = open_options;
#ifdef PMD_HAVE_HOSTTIME
        if (options.hostInterface) {
            interface = open_host;
            options.hostInterface = &interface;
        }
#endif
    } else {
        PMDFMUOptionsInit(&options);
        options.log = PMDFMU_LogTransportToStderr;
        options.logCategories = no_categories;
    }
    pthread_mutex_unlock(&open_options_lock);
    device = device_link(&options, &refused);
    if (refused)
        return PMD_ERR_OpeningPort;
    if (device)     /* the reset mode's 57600 baud unless the program opened its port at another */
        return PMDFMU_SetupAxisInterface_LineAt(handle, axis, device, baud ? baud : 57600, address, &options);
#ifdef PMD_HAVE_HOSTTIME
    if (!options.hostInterface) {
        /* PMDFMU_HOST_INTERFACE: every opening's commands timed as that kind (a program opening a parallel
           bus compared with its run over a serial line); else the link the opening names */
        const char *kind = getenv("PMDFMU_HOST_INTERFACE");
        if (kind && *kind) {
            if (PMDHostInterfaceKind(kind) < 0) {
                transport_line(&options, "PMDFMU_HOST_INTERFACE=%s: not a kind of host interface "
                               "(docs/host-time.md lists the kinds)", kind);
                return PMD_ERR_OpeningPort;
            }
            host = kind;
        }
        interface = PMDHostInterfaceOf(PMDHostInterfaceKind(host));
        if (baud)
            interface.baud = baud;
        options.hostInterface = &interface;
    }
#else
    (void)host;
    (void)baud;
#endif
    (void)address;      /* one chip in-process: it answers whatever address */
    return PMDSetupAxisInterface_FMU(handle, axis, &options);
}

static PMDresult open_twin(PMDAxisHandle *handle, PMDAxis axis, const char *host, PMDuint32 baud)
{
    return open_twin_at(handle, axis, host, baud, 0);
}

/* ---- 2.x ---- */

PMDresult PMDSetupAxisInterface_Serial(PMDAxisHandle *axis_handle, PMDAxis axis_number, PMDuint8 port_number)
{
    (void)port_number;
    return open_twin(axis_handle, axis_number, "serial", 0);
}

PMDresult PMDSetupAxisInterface_Parallel(PMDAxisHandle *axis_handle, PMDAxis axis_number, PMDuint16 board_address)
{
    (void)board_address;
    return open_twin(axis_handle, axis_number, "parallel16", 0);
}

PMDresult PMDSetupAxisInterface_PCI(PMDAxisHandle *axis_handle, PMDAxis axis_number, PMDuint8 board_number)
{
    (void)board_number;
    return open_twin(axis_handle, axis_number, "parallel16", 0);
}

PMDresult PMDSetupAxisInterface_CAN(PMDAxisHandle *axis_handle, PMDAxis axis_number, PMDuint16 baud, PMDuint8 nodeID)
{
    (void)baud;
    (void)nodeID;
    return open_twin(axis_handle, axis_number, "fixed", 0);
}

/* ---- 5.x ---- */

PMDresult PMDGetCMotionVersion(PMDuint32 *MajorVersion, PMDuint32 *MinorVersion)
{
    if (MajorVersion)
        *MajorVersion = CMOTION_MAJOR_VERSION;
    if (MinorVersion)
        *MinorVersion = CMOTION_MINOR_VERSION;
    return PMD_ERR_OK;
}

static PMDresult periph(PMDPeriphHandle *hPeriph, int type, PMDparam address, PMDparam parameter)
{
    if (!hPeriph)
        return PMD_ERR_InvalidHandle;
    hPeriph->type = type;
    hPeriph->address = address;
    hPeriph->parameter = parameter;
    hPeriph->transport_data = NULL;
    return PMD_ERR_OK;
}

PMDresult PMDDeviceOpenPeriphSerial(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDparam port, PMDparam baud,
                                    PMDparam parity, PMDparam stopbits)
{
    (void)hDevice;
    (void)parity;
    (void)stopbits;
    if (baud >= sizeof serial_baud / sizeof *serial_baud)
        return PMD_ERR_InvalidBaud;
    return periph(hPeriph, InterfaceSerial, port, baud);
}

PMDresult PMDDeviceOpenPeriphTCP(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDparam ipv4address,
                                 PMDparam portnum, PMDparam timeout)
{
    (void)hDevice;
    (void)timeout;
    return periph(hPeriph, InterfaceTCP, ipv4address, portnum);
}

PMDresult PMDDeviceOpenPeriphUDP(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDparam ipv4address,
                                 PMDparam portnum)
{
    (void)hDevice;
    return periph(hPeriph, InterfaceUDP, ipv4address, portnum);
}

PMDresult PMDDeviceOpenPeriphPIO(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDuint16 address,
                                 PMDuint8 eventIRQ, PMDparam datasize)
{
    (void)hDevice;
    (void)eventIRQ;
    return periph(hPeriph, InterfaceParallel, address, datasize);
}

PMDresult PMDDeviceOpenPeriphCAN(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDparam addressTX,
                                 PMDparam addressRX, PMDparam addressEvent)
{
    (void)hDevice;
    (void)addressEvent;
    return periph(hPeriph, InterfaceCAN, addressTX, addressRX);
}

PMDresult PMDDeviceOpenPeriphSPI(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDuint8 port,
                                 PMDuint8 chipselect, PMDuint8 mode, PMDuint8 datasize, PMDparam bitrate)
{
    (void)hDevice;
    (void)mode;
    (void)datasize;
    (void)bitrate;
    return periph(hPeriph, InterfaceSPI, port, chipselect);
}

PMDresult PMDDeviceOpenPeriphPRP(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice, PMDparam channel,
                                 PMDparam bufsize)
{
    (void)hDevice;
    return periph(hPeriph, InterfacePRP, channel, bufsize);
}

PMDresult PMDDeviceOpenPeriphCME(PMDPeriphHandle *hPeriph, PMDDeviceHandle *hDevice)
{
    (void)hDevice;
    return periph(hPeriph, InterfaceRemote, 0, 0);    /* the engine's console: no motion processor behind it */
}

/* The host interface a peripheral's link times like (PMDlibrary.h) */
static PMDresult open_device(PMDDeviceHandle *hDevice, PMDPeriphHandle *hPeriph, int type)
{
    const char *host = "fixed";
    PMDuint32 baud = 0;
    PMDresult r;
    if (!hDevice || !hPeriph)
        return PMD_ERR_InvalidHandle;
    if (hPeriph->type == InterfaceNone)
        return PMD_ERR_NotConnected;
    switch (hPeriph->type) {
    case InterfaceSerial:
        host = "serial";
        if (hPeriph->parameter < sizeof serial_baud / sizeof *serial_baud)
            baud = serial_baud[hPeriph->parameter];
        break;
    case InterfaceParallel:
    case InterfacePCI:
    case InterfaceISA:
        host = "parallel16";
        break;
    case InterfaceSPI:
        host = "spi";
        break;
    default:
        break;
    }
    r = open_twin_at(&hDevice->hAxis, PMDAxis1, host, baud, hPeriph->multidrop ? (unsigned)(hPeriph->multidrop - 1) : 0);
    if (r != PMD_ERR_OK)
        return r;
    hDevice->type = type;
    hDevice->hPeriph = hPeriph;
    return PMD_ERR_OK;
}

PMDresult PMDPeriphOpenDeviceMP(PMDDeviceHandle *hDevice, PMDPeriphHandle *hPeriph)
{
    return open_device(hDevice, hPeriph, PMDDeviceTypeMotionProcessor);
}

PMDresult PMDPeriphOpenDevicePRP(PMDDeviceHandle *hDevice, PMDPeriphHandle *hPeriph)
{
    return open_device(hDevice, hPeriph, PMDDeviceTypeResourceProtocol);
}

static PMDresult device_check(PMDDeviceHandle *hDevice)
{
    if (!hDevice)
        return PMD_ERR_InvalidHandle;
    return hDevice->type == PMDDeviceTypeNone ? PMD_ERR_InterfaceNotInitialized : PMD_ERR_OK;
}

PMDresult PMDDeviceClose(PMDDeviceHandle *hDevice)
{
    PMDresult r = device_check(hDevice);
    if (r != PMD_ERR_OK)
        return r;
    hDevice->type = PMDDeviceTypeNone;
    return PMDCloseAxisInterface(&hDevice->hAxis);
}

PMDresult PMDDeviceReset(PMDDeviceHandle *hDevice)
{
    PMDresult r;
    hDevice = engine_device(hDevice, &r);
    if (r == PMD_ERR_OK)
        r = device_check(hDevice);
    return r != PMD_ERR_OK ? r : PMDReset(&hDevice->hAxis);
}

PMDresult PMDDeviceNoOperation(PMDDeviceHandle *hDevice)
{
    PMDresult r;
    hDevice = engine_device(hDevice, &r);
    if (r == PMD_ERR_OK)
        r = device_check(hDevice);
    return r != PMD_ERR_OK ? r : PMDNoOperation(&hDevice->hAxis);
}

/* C-Motion Engine user code names its own device NULL: the engine's motion processor, on its local
   bus, opened the first time a call names it */
static PMDDeviceHandle *engine_device(PMDDeviceHandle *hDevice, PMDresult *r)
{
    *r = PMD_ERR_OK;
    if (hDevice)
        return hDevice;
    pthread_mutex_lock(&engine_lock);
    if (engine.type == PMDDeviceTypeNone) {
        *r = open_twin(&engine.hAxis, PMDAxis1, "parallel16", 0);
        if (*r == PMD_ERR_OK)
            engine.type = PMDDeviceTypeMotionProcessor;
    }
    pthread_mutex_unlock(&engine_lock);
    return &engine;
}

PMDresult PMDAxisOpen(PMDAxisHandle *hAxis, PMDDeviceHandle *hDevice, PMDAxis axis_number)
{
    PMDresult r;
    if (!hAxis)
        return PMD_ERR_InvalidHandle;
    hDevice = engine_device(hDevice, &r);
    if (r == PMD_ERR_OK)
        r = device_check(hDevice);
    return r != PMD_ERR_OK ? r : PMDCopyAxisInterface(hAxis, &hDevice->hAxis, axis_number);
}

PMDresult PMDDeviceGetVersion(PMDDeviceHandle *hDevice, PMDuint32 *major, PMDuint32 *minor)
{
    PMDuint16 generation, motorType, axes, special, custom, ma, mi;
    PMDresult r;
    hDevice = engine_device(hDevice, &r);
    if (r == PMD_ERR_OK)
        r = device_check(hDevice);
    if (r == PMD_ERR_OK)
        r = PMDGetVersion(&hDevice->hAxis, &generation, &motorType, &axes, &special, &custom, &ma, &mi);
    if (r != PMD_ERR_OK)
        return r;
    if (major)
        *major = ma;
    if (minor)
        *minor = mi;
    return PMD_ERR_OK;
}


PMDresult PMDAxisClose(PMDAxisHandle *hAxis)
{
    return PMDCloseAxisInterface(hAxis);
}

PMDresult PMDPeriphClose(PMDPeriphHandle *hPeriph)
{
    if (!hPeriph)
        return PMD_ERR_InvalidHandle;
    hPeriph->type = InterfaceNone;
    return PMD_ERR_OK;
}

PMDresult PMDPeriphFlush(PMDPeriphHandle *hPeriph)
{
    return hPeriph ? PMD_ERR_OK : PMD_ERR_InvalidHandle;
}

PMDresult PMDPeriphSend(PMDPeriphHandle *hPeriph, const void *data, PMDparam nCount, PMDparam timeoutms)
{
    (void)data;
    (void)nCount;
    (void)timeoutms;
    return hPeriph ? PMD_ERR_NotSupported : PMD_ERR_InvalidHandle;
}

PMDresult PMDPeriphReceive(PMDPeriphHandle *hPeriph, void *data, PMDparam *pnReceived, PMDparam nExpected,
                           PMDparam timeoutms)
{
    (void)data;
    (void)nExpected;
    (void)timeoutms;
    if (pnReceived)
        *pnReceived = 0;
    return hPeriph ? PMD_ERR_NotSupported : PMD_ERR_InvalidHandle;
}

PMDresult PMDPeriphRead(PMDPeriphHandle *hPeriph, void *data, PMDparam offset, PMDparam length)
{
    (void)data;
    (void)offset;
    (void)length;
    return hPeriph ? PMD_ERR_NotSupported : PMD_ERR_InvalidHandle;
}

PMDresult PMDPeriphWrite(PMDPeriphHandle *hPeriph, void *data, PMDparam offset, PMDparam length)
{
    (void)data;
    (void)offset;
    (void)length;
    return hPeriph ? PMD_ERR_NotSupported : PMD_ERR_InvalidHandle;
}

PMDresult PMDWriteDPRAM(PMDAxisInterface axis_intf, PMDuint32 *data, PMDuint32 offset_in_dwords,
                        PMDuint32 dwords_to_write)
{
    if (!axis_intf)
        return PMD_ERR_InvalidHandle;
    return PMDFMU_WriteDPRAM(&axis_intf->transport_data, offset_in_dwords, dwords_to_write, data);
}

PMDresult PMDReadDPRAM(PMDAxisInterface axis_intf, PMDuint32 *data, PMDuint32 offset_in_dwords,
                       PMDuint32 dwords_to_read)
{
    (void)data;
    (void)offset_in_dwords;
    (void)dwords_to_read;
    return axis_intf ? PMD_ERR_NotSupported : PMD_ERR_InvalidHandle;
}

void PMDTaskAbort(int UserAbortCode)
{
    fflush(stdout);
    exit(UserAbortCode);
}

PMDuint32 PMDDeviceGetTickCount(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (PMDuint32)((unsigned long long)now.tv_sec * 1000u + (unsigned long long)now.tv_nsec / 1000000u);
}

void PMDTaskWaitUntil(PMDuint32 *pPreviousTime, PMDuint32 increment)
{
    PMDTaskWait(increment);
    if (pPreviousTime)
        *pPreviousTime += increment;
}

int PMDFMU_RunUserTask(void (*task)(PMDTaskParam), const char *name)
{
    (void)name;
    task(0);
    pthread_mutex_lock(&engine_lock);
    if (engine.type != PMDDeviceTypeNone)
        PMDDeviceClose(&engine);
    pthread_mutex_unlock(&engine_lock);
    fflush(stdout);
    return 0;
}

/* ---- memory, events and what the twin has no counterpart of ---- */

PMDresult PMDDeviceOpenMemory(PMDMemoryHandle *hMemory, PMDDeviceHandle *hDevice, PMDparam datasize,
                              PMDparam memorytype)
{
    PMDresult r;
    hDevice = engine_device(hDevice, &r);
    if (r == PMD_ERR_OK)
        r = device_check(hDevice);
    if (!hMemory)
        return PMD_ERR_InvalidHandle;
    if (r != PMD_ERR_OK)
        return r;
    hMemory->hDevice = hDevice;
    hMemory->datasize = datasize;
    hMemory->memorytype = memorytype;
    return PMD_ERR_OK;
}

PMDresult PMDMemoryRead(PMDMemoryHandle *hMemory, void *data, PMDuint32 offset, PMDuint32 length)
{
    (void)data;
    (void)offset;
    (void)length;
    return hMemory ? PMD_ERR_NotSupported : PMD_ERR_InvalidHandle;
}

PMDresult PMDMemoryWrite(PMDMemoryHandle *hMemory, void *data, PMDuint32 offset, PMDuint32 length)
{
    PMDuint32 words[64];
    const unsigned char *bytes = data;
    PMDuint32 done = 0, i, n;
    PMDresult r;
    if (!hMemory || !hMemory->hDevice)
        return PMD_ERR_InvalidHandle;
    if (hMemory->memorytype != PMDMemoryAddress_DPRAM || hMemory->datasize != PMDDataSize_32Bit)
        return PMD_ERR_NotSupported;
    /* the program's 32-bit words as the host stores them (uint32_t-sized, whatever a long is) */
    while (done < length) {
        n = length - done < 64 ? length - done : 64;
        for (i = 0; i < n; i++) {
            uint32_t w;
            memcpy(&w, bytes + 4 * (done + i), 4);
            words[i] = w;
        }
        r = PMDFMU_WriteDPRAM(&hMemory->hDevice->hAxis.transport_data, offset + done, n, words);
        if (r != PMD_ERR_OK)
            return r;
        done += n;
    }
    return PMD_ERR_OK;
}

PMDresult PMDMemoryErase(PMDMemoryHandle *hMemory)
{
    return hMemory ? PMD_ERR_NotSupported : PMD_ERR_InvalidHandle;
}

PMDresult PMDMemoryClose(PMDMemoryHandle *hMemory)
{
    if (!hMemory)
        return PMD_ERR_InvalidHandle;
    hMemory->hDevice = NULL;
    return PMD_ERR_OK;
}

/* A chip at address on the parent's multi-drop line: a device opened on it sends that address in
   every packet (PMDFMU_DEVICE's links; in-process there is one chip, which answers any address) */
PMDresult PMDPeriphOpenPeriphMultiDrop(PMDPeriphHandle *hPeriph, PMDPeriphHandle *hPeriphParent, PMDparam address)
{
    if (!hPeriph || !hPeriphParent)
        return PMD_ERR_InvalidHandle;
    if (address > 0xFF)
        return PMD_ERR_InvalidParameter;
    *hPeriph = *hPeriphParent;
    hPeriph->multidrop = address + 1;
    return PMD_ERR_OK;
}

#define NOT_SUPPORTED(handle) return (handle) ? PMD_ERR_NotSupported : PMD_ERR_InvalidHandle

PMDresult PMDDeviceGetDefault(PMDDeviceHandle *hDevice, PMDparam defaultcode, void *value, PMDparam valueSize)
{
    (void)defaultcode;
    (void)value;
    (void)valueSize;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDDeviceSetDefault(PMDDeviceHandle *hDevice, PMDparam defaultcode, void *value, PMDparam valueSize)
{
    (void)defaultcode;
    (void)value;
    (void)valueSize;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDDeviceGetInfo(PMDDeviceHandle *hDevice, PMDparam infoID, PMDuint16 option, PMDuint32 *value)
{
    (void)infoID;
    (void)option;
    (void)value;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDDeviceGetResetCause(PMDDeviceHandle *hDevice, PMDuint16 *resetcause, PMDuint16 resetmask)
{
    (void)resetcause;
    (void)resetmask;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDDeviceGetFaultCode(PMDDeviceHandle *hDevice, PMDparam faultID, PMDuint32 *value)
{
    (void)faultID;
    (void)value;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDDeviceGetEvent(PMDDeviceHandle *hDevice, PMDEvent *eventdata)
{
    (void)eventdata;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDWaitForEvent(PMDDeviceHandle *hDevice, PMDEvent *eventdata, PMDparam timeout)
{
    (void)eventdata;
    (void)timeout;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDCMETaskGetState(PMDDeviceHandle *hDevice, PMDTaskState *state)
{
    (void)state;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDCMETaskStart(PMDDeviceHandle *hDevice, PMDparam taskparam)
{
    (void)taskparam;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDCMETaskStop(PMDDeviceHandle *hDevice)
{
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDCMEGetUserCodeVersion(PMDDeviceHandle *hDevice, PMDuint32 *version)
{
    (void)version;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDCMEGetUserCodeName(PMDDeviceHandle *hDevice, char *name)
{
    (void)name;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDCMEGetUserCodeDate(PMDDeviceHandle *hDevice, char *date)
{
    (void)date;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDCMESetConsole(PMDDeviceHandle *hDevice, PMDPeriphHandle *hPeriph)
{
    (void)hPeriph;
    NOT_SUPPORTED(hDevice);
}

PMDresult PMDAtlasAxisOpen(PMDAxisInterface hSourceAxis, PMDAxisInterface hAtlasAxis)
{
    (void)hAtlasAxis;
    NOT_SUPPORTED(hSourceAxis);
}

/* ---- PMDutil.h ---- */

PMDresult WaitForEvent(PMDAxisHandle *phAxis, PMDuint16 eventmask, PMDuint32 timeoutms)
{
    uint64_t start, now;
    PMDuint16 status = 0;
    PMDresult r = PMDFMU_GetHostTime(phAxis, &start);
    while (r == PMD_ERR_OK) {
        r = PMDGetEventStatus(phAxis, &status);
        if (r != PMD_ERR_OK || (status & eventmask))
            break;
        /* each poll is a command: host time passes as it does for the program's own loop */
        r = PMDFMU_GetHostTime(phAxis, &now);
        if (r == PMD_ERR_OK && now - start >= (uint64_t)timeoutms * 1000000u)
            return PMD_ERR_Timeout;
    }
    return r;
}

PMDresult ReadBuffer(PMDAxisHandle *phAxis, PMDuint16 bufferID, PMDint32 *pbuffer, PMDuint32 dwords_to_read)
{
    PMDuint32 i;
    PMDresult r = PMD_ERR_OK;
    for (i = 0; i < dwords_to_read && r == PMD_ERR_OK; i++)
        r = PMDReadBuffer(phAxis, bufferID, &pbuffer[i]);
    return r;
}

PMDresult WaitForAtlasToConnect(PMDAxisHandle *phAxis)
{
    NOT_SUPPORTED(phAxis);
}

/* PMDutil.h's phase initialization: the chip's InitializePhase, whatever it answers */
PMDresult InitializePhase(PMDAxisHandle *phAxis)
{
    return PMDInitializePhase(phAxis);
}
