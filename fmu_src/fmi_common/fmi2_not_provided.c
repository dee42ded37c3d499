/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 2.0 functions that neither FMU provides (modelDescription.xml says so:
 * canInterpolateInputs false, maxOutputDerivativeOrder 0, no directional
 * derivatives; doStep is synchronous). Every call is refused with fmi2Error
 * by the FMU's pmd_fmi2_unsupported. */
#include "fmi2.h"

fmi2Status fmi2CancelStep(fmi2Component c)
{
    return pmd_fmi2_unsupported(c, "fmi2CancelStep", "doStep never runs asynchronously");
}

#define STATUS_FUNCTION(fn, T)                                                   \
    fmi2Status fn(fmi2Component c, const fmi2StatusKind s, T *value)            \
    {                                                                            \
        (void)s; (void)value;                                                    \
        return pmd_fmi2_unsupported(c, #fn, "doStep never returns fmi2Pending"); \
    }

STATUS_FUNCTION(fmi2GetStatus, fmi2Status)
STATUS_FUNCTION(fmi2GetRealStatus, fmi2Real)
STATUS_FUNCTION(fmi2GetIntegerStatus, fmi2Integer)
STATUS_FUNCTION(fmi2GetBooleanStatus, fmi2Boolean)
STATUS_FUNCTION(fmi2GetStringStatus, fmi2String)

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer order[], const fmi2Real value[])
{
    (void)vr; (void)nvr; (void)order; (void)value;
    return pmd_fmi2_unsupported(c, "fmi2SetRealInputDerivatives", "canInterpolateInputs is false");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                        const fmi2Integer order[], fmi2Real value[])
{
    (void)vr; (void)nvr; (void)order; (void)value;
    return pmd_fmi2_unsupported(c, "fmi2GetRealOutputDerivatives", "maxOutputDerivativeOrder is 0");
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[], size_t nUnknown,
                                        const fmi2ValueReference vKnown_ref[], size_t nKnown,
                                        const fmi2Real dvKnown[], fmi2Real dvUnknown[])
{
    (void)vUnknown_ref; (void)nUnknown; (void)vKnown_ref; (void)nKnown; (void)dvKnown; (void)dvUnknown;
    return pmd_fmi2_unsupported(c, "fmi2GetDirectionalDerivative", "providesDirectionalDerivative is false");
}
