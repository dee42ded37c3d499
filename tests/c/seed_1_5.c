/* Seed 000, section 1.5 "Stopping the profile": its snippets compiled as printed. 300 cycles
   into the synchronized external profile of axes 1-3, by the first argument, the abrupt stop
   of axis 1 (`single`: SetStopMode and Update) or the synchronized stop of axes 1-3 (`multi`,
   the default: the MultiUpdate snippet); then 50 cycles, and each axis's stop mode read back.
   Around them (seed_support.h): 1.1's buffers, 1.3's upload, 1.4's initial moves and start for
   three axes. No added declaration: the snippets name only the handles and constants. */
#include "seed_support.h"

static void stop_single(void)
{
/* ---- seed 000, 1.5, first snippet ---- */
PMDSetStopMode(&hAxis[PMDAxis1],PMDAbruptStop);
PMDUpdate(&hAxis[PMDAxis1]);
/* ---- end ---- */
}

static void stop_multi(void)
{
/* ---- seed 000, 1.5, second snippet ---- */
PMDSetStopMode(&hAxis[PMDAxis1],PMDAbruptStop);
PMDSetStopMode(&hAxis[PMDAxis2],PMDAbruptStop);
PMDSetStopMode(&hAxis[PMDAxis3],PMDAbruptStop);
// the mask selects which axis is updated
PMDMultiUpdate(&hAxis[PMDAxis1],PMDAxis1Mask+PMDAxis2Mask+PMDAxis3Mask);
/* ---- end ---- */
}

int main(int argc, char **argv)
{
    int axis;
    seed_open();
    setup_buffers(3);
    populate(3);
    initial_moves(3);
    wait_at_rest(3);
    start_external(3);
    run_cycles(300);
    if (argc > 1 && strcmp(argv[1], "single") == 0)
        stop_single();
    else
        stop_multi();
    run_cycles(50);
    for (axis = 0; axis < 3; axis++) {
        PMDuint16 mode = 0xFFFF;
        check(PMDGetStopMode(&hAxis[axis], &mode), "PMDGetStopMode");
        printf("R stopmode %d %u\n", axis, mode);
    }
    seed_close();
    return 0;
}
