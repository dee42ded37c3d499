/* SPDX-License-Identifier: BSD-2-Clause */
/* Fuzz target: random FMI 2.0 call sequences on two instances:
 * set/get of every type with random value references and values, doStep
 * with random times and sizes (NaN, negative, huge), FMU state get/set/
 * serialize/deserialize with random blobs, reset, terminate. Nothing may
 * crash; the second instance is stepped alongside and must stay unaffected. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "variables.h"

static void logger(fmi2ComponentEnvironment e, fmi2String n, fmi2Status s, fmi2String c, fmi2String m, ...)
{
    (void)e; (void)n; (void)s; (void)c; (void)m;
}

static const fmi2CallbackFunctions callbacks = {logger, NULL, NULL, NULL, NULL};

typedef struct { const uint8_t *p; size_t n; } Input;

static uint32_t take(Input *in, int bytes)
{
    uint32_t v = 0;
    while (bytes-- && in->n) {
        v = v << 8 | *in->p++;
        in->n--;
    }
    return v;
}

static double take_double(Input *in)
{
    static const double special[] = {0.0, -0.0, 1e-4, -1e-4, 1e300, -1e300, 1e-300, 0.5e-4, 2.5e-4};
    uint32_t k = take(in, 1);
    if (k < 9)
        return special[k];
    if (k == 9)
        return NAN;
    if (k == 10)
        return INFINITY;
    return (double)(int32_t)take(in, 4) * 1e-6;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    Input in = {data, size};
    fmi2Component c = fmi2Instantiate("fuzz", fmi2CoSimulation, PMD_INSTANTIATION_TOKEN, "", &callbacks, 0, 0);
    fmi2Component other = fmi2Instantiate("other", fmi2CoSimulation, PMD_INSTANTIATION_TOKEN, "", &callbacks, 0, 0);
    fmi2FMUstate state = NULL;
    double t = 0, t_other = 0;
    if (!c || !other)
        abort();
    fmi2SetupExperiment(other, 0, 0, 0, 0, 0);
    fmi2EnterInitializationMode(other);
    fmi2ExitInitializationMode(other);
    while (in.n) {
        fmi2ValueReference vr[4];
        fmi2Integer ints[4];
        fmi2Real reals[4];
        fmi2Boolean bools[4];
        fmi2String strings[4] = {"", "", "", ""};
        size_t k, n = take(&in, 1) % 5;
        for (k = 0; k < n; k++) {
            vr[k] = take(&in, 2) % 2100;
            ints[k] = (fmi2Integer)take(&in, 4);
            reals[k] = take_double(&in);
            bools[k] = (fmi2Boolean)(take(&in, 1) % 3);
        }
        switch (take(&in, 1) % 22) {
        case 0: fmi2SetupExperiment(c, 0, 0, take_double(&in), 0, 0); break;
        case 1: fmi2EnterInitializationMode(c); break;
        case 2: fmi2ExitInitializationMode(c); break;
        case 3: fmi2SetInteger(c, vr, n, ints); break;
        case 4: fmi2GetInteger(c, vr, n, ints); break;
        case 5: fmi2SetReal(c, vr, n, reals); break;
        case 6: fmi2GetReal(c, vr, n, reals); break;
        case 7: fmi2SetBoolean(c, vr, n, bools); break;
        case 8: fmi2GetBoolean(c, vr, n, bools); break;
        case 9: fmi2GetString(c, vr, n, strings); break;
        case 10: { double h = take_double(&in); if (fmi2DoStep(c, t, h, 0) == fmi2OK) t += h; } break;
        case 11: fmi2DoStep(c, take_double(&in), take_double(&in), 0); break;
        case 12: fmi2GetFMUstate(c, &state); break;
        case 13: if (state) fmi2SetFMUstate(c, state); break;
        case 14: if (state) fmi2FreeFMUstate(c, &state); break;
        case 15: {
            size_t bytes = 0;
            if (state && fmi2SerializedFMUstateSize(c, state, &bytes) == fmi2OK && bytes < (1u << 22)) {
                fmi2Byte *blob = malloc(bytes ? bytes : 1);
                fmi2FMUstate restored = NULL;
                fmi2SerializeFMUstate(c, state, blob, bytes);
                if (bytes && in.n)
                    blob[take(&in, 4) % bytes] ^= (fmi2Byte)take(&in, 1);   /* maybe corrupt it */
                if (fmi2DeSerializeFMUstate(c, blob, bytes, &restored) == fmi2OK)
                    fmi2FreeFMUstate(c, &restored);
                free(blob);
            }
        } break;
        case 16: { fmi2Byte junk[64]; fmi2FMUstate s = NULL; size_t m = take(&in, 1) % 64;
                   for (k = 0; k < m; k++) junk[k] = (fmi2Byte)take(&in, 1);
                   if (fmi2DeSerializeFMUstate(c, junk, m, &s) == fmi2OK) abort(); } break;
        case 17: fmi2Reset(c); t = 0; break;
        case 18: fmi2Terminate(c); break;
        case 19: fmi2SetInteger(c, NULL, n, ints); fmi2GetReal(c, vr, n, NULL); break;
        case 20: { fmi2String cats[1] = {"warnings"}; fmi2SetDebugLogging(c, 1, 1, cats); } break;
        default:
            if (fmi2DoStep(other, t_other, 1e-4, 0) != fmi2OK)
                abort();                 /* the other instance never notices */
            t_other += 1e-4;
            break;
        }
    }
    if (state)
        fmi2FreeFMUstate(c, &state);
    fmi2FreeInstance(c);
    fmi2FreeInstance(other);
    return 0;
}
