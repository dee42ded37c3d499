/* SPDX-License-Identifier: BSD-2-Clause */
/* FMI 3.0 functions that neither FMU provides: both are Co-Simulation only,
 * with no event mode, no clocks, no structural parameters and no derivatives
 * (their modelDescription.xml say so). Every call is refused: an instantiation
 * with NULL, any other call with fmi3Error by the FMU's pmd_fmi3_unsupported. */
#include "fmi3.h"

/* The dependencies are in modelDescription.xml's ModelStructure (from
 * variables.csv and plant.csv); the API functions that would repeat them at
 * run time are not provided. */
#define NO_DEPENDENCIES_API "the dependencies are declared in modelDescription.xml; not provided through the API"

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName, fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible, fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    (void)instanceName; (void)instantiationToken; (void)resourcePath; (void)visible; (void)loggingOn;
    pmd_fmi3_refuse_instance(instanceEnvironment, logMessage, "fmi3InstantiateModelExchange: Co-Simulation only");
    return NULL;
}

fmi3Instance fmi3InstantiateScheduledExecution(fmi3String instanceName, fmi3String instantiationToken,
                                               fmi3String resourcePath, fmi3Boolean visible,
                                               fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
                                               fmi3LogMessageCallback logMessage,
                                               fmi3ClockUpdateCallback clockUpdate,
                                               fmi3LockPreemptionCallback lockPreemption,
                                               fmi3UnlockPreemptionCallback unlockPreemption)
{
    (void)instanceName; (void)instantiationToken; (void)resourcePath; (void)visible; (void)loggingOn;
    (void)clockUpdate; (void)lockPreemption; (void)unlockPreemption;
    pmd_fmi3_refuse_instance(instanceEnvironment, logMessage,
                             "fmi3InstantiateScheduledExecution: Co-Simulation only");
    return NULL;
}

fmi3Status fmi3EnterStepMode(fmi3Instance c)
{
    return pmd_fmi3_unsupported(c, "fmi3EnterStepMode", "there is no event mode: initialization leads to step mode");
}

fmi3Status fmi3EnterEventMode(fmi3Instance c)
{
    return pmd_fmi3_unsupported(c, "fmi3EnterEventMode", "hasEventMode is false");
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                    const fmi3Int32 orders[], fmi3Float64 values[], size_t nValues)
{
    (void)vrs; (void)nvr; (void)orders; (void)values; (void)nValues;
    return pmd_fmi3_unsupported(c, "fmi3GetOutputDerivatives", "maxOutputDerivativeOrder is 0");
}

fmi3Status fmi3ActivateModelPartition(fmi3Instance c, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{
    (void)clockReference; (void)activationTime;
    return pmd_fmi3_unsupported(c, "fmi3ActivateModelPartition", "Co-Simulation only");
}

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance c, fmi3ValueReference valueReference,
                                               size_t *nDependencies)
{
    (void)valueReference; (void)nDependencies;
    return pmd_fmi3_unsupported(c, "fmi3GetNumberOfVariableDependencies", NO_DEPENDENCIES_API);
}

fmi3Status fmi3GetVariableDependencies(fmi3Instance c, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[], fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[], fmi3DependencyKind dependencyKinds[],
                                       size_t nDependencies)
{
    (void)dependent; (void)elementIndicesOfDependent; (void)independents; (void)elementIndicesOfIndependents;
    (void)dependencyKinds; (void)nDependencies;
    return pmd_fmi3_unsupported(c, "fmi3GetVariableDependencies", NO_DEPENDENCIES_API);
}

#define NO_DERIVATIVES "providesDirectionalDerivatives and providesAdjointDerivatives are false"

#define NO_DERIVATIVE(fn)                                                                                   \
    fmi3Status fn(fmi3Instance c, const fmi3ValueReference unknowns[], size_t nUnknowns,                    \
                  const fmi3ValueReference knowns[], size_t nKnowns, const fmi3Float64 seed[], size_t nSeed, \
                  fmi3Float64 sensitivity[], size_t nSensitivity)                                           \
    {                                                                                                       \
        (void)unknowns; (void)nUnknowns; (void)knowns; (void)nKnowns; (void)seed; (void)nSeed;              \
        (void)sensitivity; (void)nSensitivity;                                                              \
        return pmd_fmi3_unsupported(c, #fn, NO_DERIVATIVES);                                                \
    }

NO_DERIVATIVE(fmi3GetDirectionalDerivative)
NO_DERIVATIVE(fmi3GetAdjointDerivative)

#define NO_ARGUMENTS(fn, why)                     \
    fmi3Status fn(fmi3Instance c)                 \
    {                                             \
        return pmd_fmi3_unsupported(c, #fn, why); \
    }

NO_ARGUMENTS(fmi3EnterConfigurationMode, "there are no structural parameters")
NO_ARGUMENTS(fmi3ExitConfigurationMode, "there are no structural parameters")
NO_ARGUMENTS(fmi3EvaluateDiscreteStates, "there is no event mode")
NO_ARGUMENTS(fmi3EnterContinuousTimeMode, "Co-Simulation only")

#define NO_CLOCKS "there are no clocks"

fmi3Status fmi3GetIntervalDecimal(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                  fmi3Float64 intervals[], fmi3IntervalQualifier qualifiers[])
{
    (void)vrs; (void)nvr; (void)intervals; (void)qualifiers;
    return pmd_fmi3_unsupported(c, "fmi3GetIntervalDecimal", NO_CLOCKS);
}

fmi3Status fmi3GetIntervalFraction(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                   fmi3UInt64 counters[], fmi3UInt64 resolutions[],
                                   fmi3IntervalQualifier qualifiers[])
{
    (void)vrs; (void)nvr; (void)counters; (void)resolutions; (void)qualifiers;
    return pmd_fmi3_unsupported(c, "fmi3GetIntervalFraction", NO_CLOCKS);
}

fmi3Status fmi3GetShiftDecimal(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, fmi3Float64 shifts[])
{
    (void)vrs; (void)nvr; (void)shifts;
    return pmd_fmi3_unsupported(c, "fmi3GetShiftDecimal", NO_CLOCKS);
}

fmi3Status fmi3GetShiftFraction(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr, fmi3UInt64 counters[],
                                fmi3UInt64 resolutions[])
{
    (void)vrs; (void)nvr; (void)counters; (void)resolutions;
    return pmd_fmi3_unsupported(c, "fmi3GetShiftFraction", NO_CLOCKS);
}

fmi3Status fmi3SetIntervalDecimal(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                  const fmi3Float64 intervals[])
{
    (void)vrs; (void)nvr; (void)intervals;
    return pmd_fmi3_unsupported(c, "fmi3SetIntervalDecimal", NO_CLOCKS);
}

fmi3Status fmi3SetIntervalFraction(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                   const fmi3UInt64 counters[], const fmi3UInt64 resolutions[])
{
    (void)vrs; (void)nvr; (void)counters; (void)resolutions;
    return pmd_fmi3_unsupported(c, "fmi3SetIntervalFraction", NO_CLOCKS);
}

fmi3Status fmi3SetShiftDecimal(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                               const fmi3Float64 shifts[])
{
    (void)vrs; (void)nvr; (void)shifts;
    return pmd_fmi3_unsupported(c, "fmi3SetShiftDecimal", NO_CLOCKS);
}

fmi3Status fmi3SetShiftFraction(fmi3Instance c, const fmi3ValueReference vrs[], size_t nvr,
                                const fmi3UInt64 counters[], const fmi3UInt64 resolutions[])
{
    (void)vrs; (void)nvr; (void)counters; (void)resolutions;
    return pmd_fmi3_unsupported(c, "fmi3SetShiftFraction", NO_CLOCKS);
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance c, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation, fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged, fmi3Boolean *nextEventTimeDefined,
                                    fmi3Float64 *nextEventTime)
{
    (void)discreteStatesNeedUpdate; (void)terminateSimulation; (void)nominalsOfContinuousStatesChanged;
    (void)valuesOfContinuousStatesChanged; (void)nextEventTimeDefined; (void)nextEventTime;
    return pmd_fmi3_unsupported(c, "fmi3UpdateDiscreteStates", "there is no event mode");
}

/* Model Exchange functions: both FMUs are Co-Simulation only. */
#define ME_ONLY "Co-Simulation only"

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance c, fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode, fmi3Boolean *terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint; (void)enterEventMode; (void)terminateSimulation;
    return pmd_fmi3_unsupported(c, "fmi3CompletedIntegratorStep", ME_ONLY);
}

fmi3Status fmi3SetTime(fmi3Instance c, fmi3Float64 time)
{
    (void)time;
    return pmd_fmi3_unsupported(c, "fmi3SetTime", ME_ONLY);
}

#define STATE_VECTOR(fn, T)                                              \
    fmi3Status fn(fmi3Instance c, T values[], size_t n)                  \
    {                                                                    \
        (void)values; (void)n;                                           \
        return pmd_fmi3_unsupported(c, #fn, ME_ONLY);                   \
    }

STATE_VECTOR(fmi3SetContinuousStates, const fmi3Float64)
STATE_VECTOR(fmi3GetContinuousStateDerivatives, fmi3Float64)
STATE_VECTOR(fmi3GetEventIndicators, fmi3Float64)
STATE_VECTOR(fmi3GetContinuousStates, fmi3Float64)
STATE_VECTOR(fmi3GetNominalsOfContinuousStates, fmi3Float64)

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance c, size_t *nEventIndicators)
{
    (void)nEventIndicators;
    return pmd_fmi3_unsupported(c, "fmi3GetNumberOfEventIndicators", ME_ONLY);
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance c, size_t *nContinuousStates)
{
    (void)nContinuousStates;
    return pmd_fmi3_unsupported(c, "fmi3GetNumberOfContinuousStates", ME_ONLY);
}
