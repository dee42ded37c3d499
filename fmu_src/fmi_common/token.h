/* SPDX-License-Identifier: BSD-2-Clause */
/* Which instantiation token (FMI 2: the GUID) an FMU's binary accepts.
 *
 * The token says which variables a model description describes. The binary's
 * own (pmd_model_token, model.h) is a fingerprint of the interface tables it
 * was generated from. A packed FMU (pmdfmu pack, python/pmdfmu/pack.py) has the
 * same variables but an identity of its own, so that two packed profiles in one
 * system are told apart: its token is the binary's token, '+', and a
 * fingerprint of the packed FMU's contents, and its resources folder holds that
 * token in PMD_TOKEN_FILE. The binary accepts its own token, or the packed
 * token written there.
 *
 * The file can only widen what the binary accepts to tokens that begin with its
 * own, i.e. to model descriptions that claim this binary's variables: a packed
 * FMU whose binary was swapped for another build's, or whose file was edited to
 * another binary's token, is refused, whatever token the importer gives (a file
 * that is not a token of this binary is an error, never ignored). Like any
 * fingerprint, the token guards against mistakes, not against a forger, who can
 * as well edit the model description. */
#ifndef PMD_TOKEN_H
#define PMD_TOKEN_H

#include <stddef.h>

#define PMD_TOKEN_FILE "instantiation.token"

/* Whether `given` is a token of this FMU, the resources folder (ending in a
 * separator, or NULL with why in noResources) holding the packed token if
 * any: 1, or 0 with a sentence in why that begins with fn ("fn: the what ...";
 * what is "GUID" or "instantiation token"). */
int pmd_token_accepted(const char *fn, const char *what, const char *given, const char *resources,
                       const char *noResources, char *why, size_t whySize);

#endif
