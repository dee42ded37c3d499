/* SPDX-License-Identifier: BSD-2-Clause */
/* The plant: a DC motor behind an amplifier, driving an inertia against
 * viscous and Coulomb friction, read by a quadrature encoder. Plain data and
 * plain functions, nothing of FMI (plant_fmu.c is the FMU around it).
 *
 *   V  = supplyVoltage * u                     u: motorCommand / 32768 + motorOutput, clamped to -1..1
 *   i  = (V - k w) / R                         k: torqueConstant (= back-EMF constant), R: armatureResistance
 *   J dw/dt = k i - b w - Tc sgn(w) + loadTorque   J = rotorInertia + loadInertia,
 *                                              b: viscousFriction, Tc: coulombFriction
 *   dtheta/dt = w
 *   encoderCount = floor(theta * 4 encoderLines / 2 pi), wrapped to 32 bits
 *
 * With no inductance the armature current follows the speed at once, so the
 * motor is first order in the speed: J dw/dt = T0 - c w - Tc sgn(w), with the
 * drive torque T0 = k V / R + loadTorque and the damping c = k^2 / R + b
 * (back-EMF through the armature and viscous friction act alike). Its time
 * constant is J / c and its steady speed (T0 - Tc) / c for T0 > Tc. At rest,
 * Coulomb friction holds the shaft while |T0| <= Tc. docs/systems.md says what
 * the start values (modelDescription/plant.csv) make of it in the chip's
 * counts and cycles. */
#ifndef PLANT_H
#define PLANT_H

#include <stdint.h>

/* Each member is a variable of plant.csv of the same name (plant_variables.c
 * checks that the table and this struct agree). */
typedef struct {
    double time;                 /* the last communication point */

    /* parameters */
    double supplyVoltage;        /* V */
    double armatureResistance;   /* Ohm */
    double torqueConstant;       /* N.m/A = V.s/rad */
    double rotorInertia;         /* kg.m2 */
    double loadInertia;          /* kg.m2 */
    double viscousFriction;      /* N.m.s/rad */
    double coulombFriction;      /* N.m */
    int32_t encoderLines;        /* 4x decoding: 4 encoderLines counts per revolution */
    double internalStep;         /* s */
    double initialAngle;         /* rad */
    double initialSpeed;         /* rad/s */

    /* inputs */
    int32_t motorCommand;        /* -32768..32767, full scale 32768 (2^15) */
    double loadTorque;           /* N.m */
    double motorOutput;          /* fraction of full scale, -1..1 */

    /* the state (angle, speed) and what the last step leaves in the outputs */
    int32_t encoderCount;
    double angle;                /* rad */
    double speed;                /* rad/s */
    double current;              /* A */
    double voltage;              /* V */
} PlantModel;

/* The state at the start time: initialAngle, initialSpeed, no current yet. */
void plant_start(PlantModel *m);

/* The encoder count of the angle (4x decoding, wrapped to 32 bits). */
int32_t plant_encoder_count(const PlantModel *m);

/* The number of internal steps plant_advance(m, h) takes (whole steps and a
 * shorter last one), for a caller that bounds the work of one call. */
double plant_internal_steps(const PlantModel *m, double h);

/* Advances the state by h seconds under the inputs as they are: whole internal
 * steps, then one step of the rest when it is longer than 1e-9 internal steps.
 * The result depends on h and the inputs only, not on the time. */
void plant_advance(PlantModel *m, double h);

#endif
