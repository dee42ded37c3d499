/* SPDX-License-Identifier: BSD-2-Clause */
/* Benchmark 3's baseline: an FMI 2.0 Co-Simulation FMU with the same
 * variables as PMDMotionProcessor that does nothing: Set stores, Get returns,
 * DoStep returns. The bench packs it with the real modelDescription.xml. */
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

#define VR_COUNT 2048

typedef struct {
    fmi2Real real[VR_COUNT];
    fmi2Integer integer[VR_COUNT];
    fmi2Boolean boolean[VR_COUNT];
} Trivial;

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Component fmi2Instantiate(fmi2String n, fmi2Type t, fmi2String g, fmi2String r, const fmi2CallbackFunctions *f,
                              fmi2Boolean v, fmi2Boolean l)
{
    (void)n; (void)t; (void)g; (void)r; (void)f; (void)v; (void)l;
    return calloc(1, sizeof(Trivial));
}

void fmi2FreeInstance(fmi2Component c) { free(c); }

#define COPY(name, T, field, dir)                                                                  \
    fmi2Status name(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, dir T value[])   \
    {                                                                                              \
        size_t i;                                                                                  \
        for (i = 0; i < nvr; i++)                                                                  \
            if (vr[i] < VR_COUNT)                                                                  \
                COPY_##dir(((Trivial *)c)->field[vr[i]], value[i]);                                \
        return fmi2OK;                                                                             \
    }
#define COPY_(store, v) (v) = (store)
#define COPY_const(store, v) (store) = (v)

COPY(fmi2GetReal, fmi2Real, real, )
COPY(fmi2GetInteger, fmi2Integer, integer, )
COPY(fmi2GetBoolean, fmi2Boolean, boolean, )
COPY(fmi2SetReal, fmi2Real, real, const)
COPY(fmi2SetInteger, fmi2Integer, integer, const)
COPY(fmi2SetBoolean, fmi2Boolean, boolean, const)

#define UNUSED(x) (void)(x)

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean l, size_t n, const fmi2String s[])
{ UNUSED(c); UNUSED(l); UNUSED(n); UNUSED(s); return fmi2OK; }
fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean a, fmi2Real b, fmi2Real d, fmi2Boolean e, fmi2Real f)
{ UNUSED(c); UNUSED(a); UNUSED(b); UNUSED(d); UNUSED(e); UNUSED(f); return fmi2OK; }
fmi2Status fmi2EnterInitializationMode(fmi2Component c) { UNUSED(c); return fmi2OK; }
fmi2Status fmi2ExitInitializationMode(fmi2Component c) { UNUSED(c); return fmi2OK; }
fmi2Status fmi2Terminate(fmi2Component c) { UNUSED(c); return fmi2OK; }
fmi2Status fmi2Reset(fmi2Component c) { UNUSED(c); return fmi2OK; }
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2String v[])
{ size_t i; UNUSED(c); UNUSED(vr); for (i = 0; i < n; i++) v[i] = ""; return fmi2OK; }
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2String v[])
{ UNUSED(c); UNUSED(vr); UNUSED(n); UNUSED(v); return fmi2OK; }
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean b)
{ UNUSED(c); UNUSED(t); UNUSED(h); UNUSED(b); return fmi2OK; }
fmi2Status fmi2CancelStep(fmi2Component c) { UNUSED(c); return fmi2Error; }
fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *v) { UNUSED(c); UNUSED(s); UNUSED(v); return fmi2Error; }
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *v) { UNUSED(c); UNUSED(s); UNUSED(v); return fmi2Error; }
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *v) { UNUSED(c); UNUSED(s); UNUSED(v); return fmi2Error; }
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *v) { UNUSED(c); UNUSED(s); UNUSED(v); return fmi2Error; }
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *v) { UNUSED(c); UNUSED(s); UNUSED(v); return fmi2Error; }
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *s) { UNUSED(c); UNUSED(s); return fmi2Error; }
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) { UNUSED(c); UNUSED(s); return fmi2Error; }
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *s) { UNUSED(c); UNUSED(s); return fmi2Error; }
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t *n) { UNUSED(c); UNUSED(s); UNUSED(n); return fmi2Error; }
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n) { UNUSED(c); UNUSED(s); UNUSED(b); UNUSED(n); return fmi2Error; }
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *s) { UNUSED(c); UNUSED(s); UNUSED(b); UNUSED(n); return fmi2Error; }
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference a[], size_t b, const fmi2ValueReference d[], size_t e, const fmi2Real f[], fmi2Real g[])
{ UNUSED(c); UNUSED(a); UNUSED(b); UNUSED(d); UNUSED(e); UNUSED(f); UNUSED(g); return fmi2Error; }
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference a[], size_t b, const fmi2Integer d[], const fmi2Real e[])
{ UNUSED(c); UNUSED(a); UNUSED(b); UNUSED(d); UNUSED(e); return fmi2Error; }
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference a[], size_t b, const fmi2Integer d[], fmi2Real e[])
{ UNUSED(c); UNUSED(a); UNUSED(b); UNUSED(d); UNUSED(e); return fmi2Error; }
