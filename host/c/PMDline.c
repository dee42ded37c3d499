/* SPDX-License-Identifier: BSD-2-Clause */
/* The line transport (PMDline.h): POSIX termios for a serial port, sockets for TCP. */
#define _XOPEN_SOURCE 700     /* getaddrinfo, clock_gettime */
#define _DEFAULT_SOURCE       /* cfmakeraw, the B* speeds above 38400 */
#include <errno.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "c-motion.h"
#include "PMDline.h"
#include "PMDserial.h"

/* How long a reply may take, and each resynchronising byte's wait (C-Motion S1: up to 8 tries) */
#define REPLY_TIMEOUT_MS 2000
#define RESYNC_WAIT_MS 50
#define RESYNC_TRIES 8

struct PMDLine {
    int fd;
    int monitor;        /* the twin's monitor's socket, or -1 */
    uint8_t address;
};

static speed_t speed_of(PMDuint32 baud)
{
    switch (baud) {
    case 1200: return B1200;
    case 2400: return B2400;
    case 9600: return B9600;
    case 19200: return B19200;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    default: return B57600;
    }
}

static int open_serial(const char *path, PMDuint32 baud, char *why, size_t size)
{
    struct termios t;
    struct stat s;
    int fd = open(path, O_RDWR | O_NOCTTY);
    if (fd < 0) {
        snprintf(why, size, "%s: %s", path, strerror(errno));
        return -1;
    }
    /* a regular file is no line: the packets were written into the user's file (a typo in the path) */
    if (fstat(fd, &s) == 0 && S_ISREG(s.st_mode)) {
        close(fd);
        snprintf(why, size, "%s: a regular file, not a serial line: nothing was written", path);
        return -1;
    }
    /* raw 8N1 (a file that is no tty is used as it is) */
    if (tcgetattr(fd, &t) == 0) {
        cfmakeraw(&t);
        cfsetispeed(&t, speed_of(baud));
        cfsetospeed(&t, speed_of(baud));
        t.c_cflag |= CLOCAL | CREAD;
        tcsetattr(fd, TCSANOW, &t);
    }
    return fd;
}

static int open_tcp(const char *where, char *why, size_t size)
{
    char host[256];
    const char *colon = strrchr(where, ':');
    struct addrinfo hints, *list = NULL, *a;
    const char *p;
    unsigned long port = 0;
    int fd = -1, e, one = 1;
    size_t n = colon ? (size_t)(colon - where) : 0;
    if (!colon || n == 0 || n >= sizeof host || !colon[1]) {
        snprintf(why, size, "expected tcp:HOST:PORT");
        return -1;
    }
    for (p = colon + 1; *p >= '0' && *p <= '9'; p++)     /* by value: 000080 is port 80, as in the harness */
        if ((port = port * 10 + (unsigned long)(*p - '0')) > 65535)
            break;
    if (port > 65535 && p[strspn(p, "0123456789")] == '\0') {
        /* getaddrinfo takes 99999 as 99999 mod 65536: another server's port */
        snprintf(why, size, "port %s is not 0 .. 65535", colon + 1);
        return -1;
    }
    memcpy(host, where, n);
    host[n] = '\0';
    if (host[0] == '[' && n > 2 && host[n - 1] == ']') {       /* [::1] */
        memmove(host, host + 1, n - 2);
        host[n - 2] = '\0';
    }
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    e = getaddrinfo(host, colon + 1, &hints, &list);
    if (e != 0) {
        snprintf(why, size, "%s: %s", host, gai_strerror(e));
        return -1;
    }
    for (a = list; a; a = a->ai_next) {
        fd = socket(a->ai_family, a->ai_socktype, a->ai_protocol);
        if (fd >= 0 && connect(fd, a->ai_addr, a->ai_addrlen) == 0)
            break;
        e = errno;
        if (fd >= 0)
            close(fd);
        fd = -1;
    }
    freeaddrinfo(list);
    if (fd < 0) {
        snprintf(why, size, "cannot connect: %s", strerror(e));
        return -1;
    }
    /* one small packet per command: no coalescing delay */
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    return fd;
}

PMDresult PMDLineOpen(PMDLine **line, const char *device, PMDuint32 baud, unsigned address, char *why, size_t size)
{
    int fd = -1;
    *line = NULL;
    if (strncmp(device, "serial:", 7) == 0 && device[7])
        fd = open_serial(device + 7, baud, why, size);
    else if (strncmp(device, "tcp:", 4) == 0)
        fd = open_tcp(device + 4, why, size);
    else
        snprintf(why, size, "expected serial:PATH or tcp:HOST:PORT");
    if (fd < 0)
        return PMD_ERR_OpeningPort;
    *line = calloc(1, sizeof **line);
    if (!*line) {
        close(fd);
        snprintf(why, size, "out of memory");
        return PMD_ERR_OpeningPort;
    }
    (*line)->fd = fd;
    (*line)->monitor = -1;
    (*line)->address = (uint8_t)address;
    return PMD_ERR_OK;
}

void PMDLineClose(PMDLine *line)
{
    if (line) {
        close(line->fd);
        if (line->monitor >= 0)
            close(line->monitor);
        free(line);
    }
}

static int write_all(int fd, const uint8_t *data, size_t n)
{
    while (n) {
        ssize_t w = write(fd, data, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        data += w;
        n -= (size_t)w;
    }
    return 0;
}

static long long now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (long long)t.tv_sec * 1000 + t.tv_nsec / 1000000;
}

/* Reads up to n bytes within timeout_ms; returns how many came. */
static size_t read_some(int fd, uint8_t *data, size_t n, int timeout_ms)
{
    size_t got = 0;
    long long end = now_ms() + timeout_ms;
    while (got < n) {
        struct pollfd p = {fd, POLLIN, 0};
        long long left = end - now_ms();
        ssize_t r;
        if (left <= 0 || poll(&p, 1, (int)left) <= 0)
            break;
        r = read(fd, data + got, n - got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            break;
        got += (size_t)r;
    }
    return got;
}

int PMDLineHasMonitor(const PMDLine *line)
{
    return line && line->monitor >= 0;
}

PMDresult PMDLineMonitorOpen(PMDLine *line, const char *monitor, char *why, size_t size)
{
    char request[32], value[PMD_LINE_MONITOR_REPLY];
    PMDresult r;
    if (strncmp(monitor, "tcp:", 4) != 0) {
        snprintf(why, size, "expected tcp:HOST:PORT");
        return PMD_ERR_OpeningPort;
    }
    line->monitor = open_tcp(monitor + 4, why, size);
    if (line->monitor < 0)
        return PMD_ERR_OpeningPort;
    snprintf(request, sizeof request, "chip %u", (unsigned)line->address);
    r = PMDLineMonitor(line, request, value, sizeof value);
    if (r != PMD_ERR_OK) {
        snprintf(why, size, "%s: %s", request, r == PMD_ERR_Driver ? value : "no answer");
        close(line->monitor);
        line->monitor = -1;
        return PMD_ERR_OpeningPort;
    }
    return PMD_ERR_OK;
}

PMDresult PMDLineMonitor(PMDLine *line, const char *request, char *value, size_t size)
{
    char in[PMD_LINE_MONITOR_REPLY];
    size_t got = 0;
    const char *text;
    if (write_all(line->monitor, (const uint8_t *)request, strlen(request)) != 0 ||
        write_all(line->monitor, (const uint8_t *)"\n", 1) != 0)
        return PMD_ERR_NotResponding;
    /* the reply's line: as long as the request takes (a run of many cycles), until the server goes */
    while (got < sizeof in - 1 && (got == 0 || in[got - 1] != '\n')) {
        ssize_t r = read(line->monitor, in + got, 1);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return PMD_ERR_NotResponding;
        got++;
    }
    if (got == 0 || in[got - 1] != '\n')
        return PMD_ERR_NotResponding;
    in[got - 1] = '\0';
    if (strcmp(in, "ok") == 0 || strncmp(in, "ok ", 3) == 0)
        text = in[2] ? in + 3 : "";
    else if (strncmp(in, "error ", 6) == 0)
        text = in + 6;
    else
        return PMD_ERR_NotResponding;
    snprintf(value, size, "%s", text);
    return in[0] == 'o' ? PMD_ERR_OK : PMD_ERR_Driver;
}

static void drain(int fd)
{
    uint8_t junk[256];
    while (read_some(fd, junk, sizeof junk, 0) > 0)
        ;
}

/* C-Motion's resynchronisation: single zero bytes until the chip completes a packet with them and
   answers with 2 bytes. */
static int resync(PMDLine *line)
{
    uint8_t zero = 0, reply[2];
    int i;
    drain(line->fd);
    for (i = 0; i < RESYNC_TRIES; i++) {
        if (write_all(line->fd, &zero, 1) != 0)
            return -1;
        if (read_some(line->fd, reply, 2, RESYNC_WAIT_MS) == 2) {
            drain(line->fd);
            return 0;
        }
    }
    return -1;
}

PMDresult PMDLineCommand(PMDLine *line, PMDuint16 instruction, const PMDuint16 *args, int nargs, PMDuint16 *reply,
                         int nreply)
{
    uint8_t packet[PMD_SERIAL_MAX_PACKET], in[2 + 2 * PMD_SERIAL_MAX_REPLY], status;
    uint16_t words[PMD_SERIAL_MAX_REPLY], a[PMD_SERIAL_MAX_ARGS];
    size_t n, got;
    int i, attempt, count;
    if (nargs < 0 || nargs > PMD_SERIAL_MAX_ARGS || nreply < 0 || nreply > PMD_SERIAL_MAX_REPLY)
        return PMD_ERR_InvalidHandle;
    for (i = 0; i < nargs; i++)
        a[i] = (uint16_t)args[i];
    n = PMDSerialCommandPacket(packet, line->address, instruction, a, nargs);
    for (attempt = 0; attempt < 2; attempt++) {
        if (write_all(line->fd, packet, n) != 0)
            return PMD_ERR_WriteError;
        got = read_some(line->fd, in, 2, REPLY_TIMEOUT_MS);
        /* an error reply is the 2 bytes alone (reference 3.2) */
        if (got == 2 && !(in[0] != 0 && PMDSerialChecksum(in, 2) == 0))
            got += read_some(line->fd, in + 2, 2 * (size_t)nreply, REPLY_TIMEOUT_MS);
        if (PMDSerialParseReply(in, got, 0, &status, words, nreply, &count) != 0 ||
            (status == 0 && count != nreply) || status == PMD_ERR_MP_BadSerialChecksum) {
            if (resync(line) != 0)
                return PMD_ERR_NotResponding;
            continue;
        }
        for (i = 0; status == 0 && i < nreply; i++)
            reply[i] = words[i];
        return status;
    }
    return PMD_ERR_NotResponding;
}
