/* Seed 000, section 1.4 "Starting the profile": its snippets compiled as printed. The initial
   moves of axes 1 and 2, then, by the first argument, the start of axis 1 alone (`update`: the
   SetProfileMode and Update snippet) or the synchronized start of axes 1-3 (`multiupdate`, the
   default: the MultiUpdate snippet). As printed, axis 3 makes no initial move (the snippet moves
   axes 1 and 2): it starts its table from where it stands.
   Around them (seed_support.h): 1.1's buffers for three axes, 1.3's WriteBuffer upload, the
   wait until the axes are at rest, the cycles run. Added declarations: data (the tables,
   PMDUINT32 as in 1.3), max_vel and max_acc (seed_support.h). */
#include "seed_support.h"

static PMDUINT32 data[3][seed_variables][SEED_ENTRIES];

static void initial_moves_1_4(void)
{
/* ---- seed 000, 1.4, first snippet ---- */
// move axis#1 to its starting location
PMDSetProfileMode(&hAxis[PMDAxis1],PMDTrapezoidal);
PMDSetVelocity(&hAxis[PMDAxis1],max_vel);
PMDSetAcceleration(&hAxis[PMDAxis1],max_acc);
PMDSetPosition(&hAxis[PMDAxis1],data[PMDAxis1][PMDBufferFunctionPosition][0]);
PMDUpdate(&hAxis[PMDAxis1]);
// move axis#2 to its starting location
PMDSetProfileMode(&hAxis[PMDAxis2],PMDTrapezoidal);
PMDSetVelocity(&hAxis[PMDAxis2],max_vel);
PMDSetAcceleration(&hAxis[PMDAxis2],max_acc);
PMDSetPosition(&hAxis[PMDAxis2],data[PMDAxis2][PMDBufferFunctionPosition][0]);
PMDUpdate(&hAxis[PMDAxis2]);
/* ---- end ---- */
}

static void start_1_4_update(void)
{
/* ---- seed 000, 1.4, second snippet ---- */
PMDSetProfileMode(&hAxis[PMDAxis1],PMDExternalProfile);
PMDUpdate(&hAxis[PMDAxis1]);
/* ---- end ---- */
}

static void start_1_4_multiupdate(void)
{
/* ---- seed 000, 1.4, third snippet ---- */
PMDSetProfileMode(&hAxis[PMDAxis1],PMDExternalProfile);
PMDSetProfileMode(&hAxis[PMDAxis2],PMDExternalProfile);
PMDSetProfileMode(&hAxis[PMDAxis3],PMDExternalProfile);
// the mask selects which axis is updated
PMDMultiUpdate(&hAxis[PMDAxis1],PMDAxis1Mask+PMDAxis2Mask+PMDAxis3Mask);
/* ---- end ---- */
}

int main(int argc, char **argv)
{
    int axis, variable, index;
    for (axis = 0; axis < 3; axis++)
        for (variable = 0; variable < seed_variables; variable++)
            for (index = 0; index < SEED_ENTRIES; index++)
                data[axis][variable][index] = (PMDUINT32)seed_entry(axis, variable, index);
    seed_open();
    setup_buffers(3);
    populate(3);
    initial_moves_1_4();
    wait_at_rest(3);
    if (argc > 1 && strcmp(argv[1], "update") == 0)
        start_1_4_update();
    else
        start_1_4_multiupdate();
    run_cycles(1500);
    seed_close();
    return 0;
}
