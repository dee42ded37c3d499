/* SPDX-License-Identifier: BSD-2-Clause */
/* The instantiation token's check, for both shells (token.h: which tokens, and why a packed FMU's file can
 * only name tokens of this binary). */
#if !defined(_WIN32) && !defined(_POSIX_C_SOURCE)
#define _POSIX_C_SOURCE 200809L      /* open, fstat, O_CLOEXEC: the build is strict C99 */
#endif
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#ifndef _WIN32
#include <fcntl.h>
#include <unistd.h>
#endif

#include "model.h"
#include "token.h"

/* More than any token pack writes (the binary's, '+' and a braced UUID): a longer file holds no token. */
#define MAX_TOKEN 127

/* Reads the file at path into token[MAX_TOKEN + 2] (a byte more than a token, to tell a longer file) and
 * its length into *length: 1, 0 if there is no such file, -1 with why. A FIFO or a folder of that name is
 * refused, not waited on. */
static int read_token_file(const char *path, char *token, size_t *length, const char **why)
{
    size_t n = 0;
#ifdef _WIN32
    struct _stat st;
    FILE *file;
    if (_stat(path, &st) != 0)
        return errno == ENOENT ? 0 : (*why = strerror(errno), -1);
    if ((st.st_mode & _S_IFMT) != _S_IFREG)
        return *why = "not a regular file", -1;
    if (!(file = fopen(path, "rb")))
        return *why = strerror(errno), -1;
    n = fread(token, 1, MAX_TOKEN + 1, file);
    if (ferror(file)) {
        *why = strerror(errno);
        fclose(file);
        return -1;
    }
    fclose(file);
#else
    struct stat st;
    ssize_t got = 1;
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return errno == ENOENT ? 0 : (*why = strerror(errno), -1);
    if (fstat(fd, &st) != 0)
        *why = strerror(errno), got = -1;
    else if (!S_ISREG(st.st_mode))
        *why = "not a regular file", got = -1;
    while (got > 0 && n <= MAX_TOKEN) {
        got = read(fd, token + n, MAX_TOKEN + 1 - n);
        if (got > 0)
            n += (size_t)got;
        else if (got < 0 && errno == EINTR)
            got = 1;
        else if (got < 0)
            *why = strerror(errno);
    }
    close(fd);
    if (got < 0)
        return -1;
#endif
    token[n] = '\0';
    *length = n;
    return 1;
}

/* Whether text is this binary's token, '+', then 1 to 64 characters of a fingerprint (pack writes a
 * braced UUID): letters, digits, '{', '}' and '-'. */
static int is_packed_token(const char *text)
{
    size_t own = strlen(pmd_model_token), i;
    if (strncmp(text, pmd_model_token, own) != 0 || text[own] != '+')
        return 0;
    for (i = own + 1; text[i]; i++)
        if (!((text[i] >= '0' && text[i] <= '9') || (text[i] >= 'a' && text[i] <= 'z') ||
              (text[i] >= 'A' && text[i] <= 'Z') || text[i] == '{' || text[i] == '}' || text[i] == '-'))
            return 0;
    return i > own + 1 && i <= own + 65;
}

int pmd_token_accepted(const char *fn, const char *what, const char *given, const char *resources,
                       const char *noResources, char *why, size_t whySize)
{
    char path[4096], packed[MAX_TOKEN + 2];
    const char *cannot = "";
    size_t length = 0;
    int found = 0;
    if (resources) {
        size_t n = strlen(resources);
        int separator = n > 0 && (resources[n - 1] == '/' || resources[n - 1] == '\\');
        if (snprintf(path, sizeof path, "%s%s" PMD_TOKEN_FILE, resources, separator ? "" : "/") >= (int)sizeof path) {
            snprintf(why, whySize, "%s: the resources folder's path is longer than %d characters", fn,
                     (int)(sizeof path - sizeof PMD_TOKEN_FILE - 1));
            return 0;
        }
        if ((found = read_token_file(path, packed, &length, &cannot)) < 0) {
            snprintf(why, whySize, "%s: cannot read the packed FMU's %s: %s: %s", fn, what, path, cannot);
            return 0;
        }
        /* a line end after the token, as an editor leaves it, is not part of it */
        while (length > 0 && (packed[length - 1] == '\n' || packed[length - 1] == '\r'))
            packed[--length] = '\0';
        /* the file's token is refused whatever the importer gives: never ignored, never half used */
        if (found && (length > MAX_TOKEN || strlen(packed) != length || !is_packed_token(packed))) {
            snprintf(why, whySize, "%s: %s holds no packed %s of this binary (one begins with its %s and '+'): "
                     "the FMU was packed onto another binary, or the file was altered; pack the profile again "
                     "onto this binary's FMU", fn, path, what, pmd_model_token);
            return 0;
        }
    }
    if (given && (strcmp(given, pmd_model_token) == 0 || (found && strcmp(given, packed) == 0)))
        return 1;
    if (!given)
        snprintf(why, whySize, "%s: the %s is NULL", fn, what);
    else if (found)
        snprintf(why, whySize, "%s: the %s %.100s matches neither this binary's %s nor this packed FMU's %s "
                 "(resources/" PMD_TOKEN_FILE "): the model description is not this FMU's", fn, what, given,
                 pmd_model_token, packed);
    else if (resources)
        snprintf(why, whySize, "%s: the %s %.100s does not match this binary's %s", fn, what, given,
                 pmd_model_token);
    else
        snprintf(why, whySize, "%s: the %s %.100s does not match this binary's %s (nor can a packed FMU's be "
                 "read: %s)", fn, what, given, pmd_model_token, noResources ? noResources : "no resources folder");
    return 0;
}
