/* Seed 000, section 1.6 "Detecting the completion of motion": its snippet compiled as printed,
   and the completion detection its text describes.
   Around it (seed_support.h): 1.1's buffers, 1.3's upload, 1.4's initial moves for three axes.
   Added declaration: axis, the breakpoint's source axis the snippet names (axis 1, as in
   tests/test_sample_code.py).

   The snippet is compiled as printed, `PMDUpdate(PMDAxis1)` included: it passes the axis number
   where every other call passes the handle. It compiles (PMDAxis1 is 0, a null pointer
   constant) and the library answers PMD_ERR_InvalidHandle (0x1106) without sending anything;
   the chip never sees the Update, so the external profile does not start (on PMD's C-Motion the
   call would dereference NULL). The snippet's two paragraphs are two functions, so that main can
   show the call's result and, with the argument `meant`, make the Update the text means,
   PMDUpdate(&hAxis[PMDAxis1]), between them:
     (none) | poll   as printed: the Update is refused, the profile never starts
     meant [poll]    the meant Update too: the breakpoint raises the host interrupt at completion
                     (run), or the host polls the activity status until the profile segment
                     number is 0 (poll) -- a loop that ends only because host time passes */
#include "seed_support.h"

static int axis = PMDAxis1;

static void start_1_6(void)
{
/* ---- seed 000, 1.6 ---- */
// start motion
PMDSetProfileMode(&hAxis[PMDAxis1],PMDExternalProfile);
PMDUpdate(PMDAxis1);
/* ---- (the snippet goes on) ---- */
}

static void breakpoint_1_6(void)
{
/* ---- seed 000, 1.6 (continued) ---- */
// program a breakpoint to generate an interrupt upon
// completion of the profile
PMDSetInterruptMask(&hAxis[PMDAxis1],PMDEventBreakpoint1Mask);
// when bit 13 of the activity status register goes low,
// the profile has finished
PMDSetBreakpointValue(&hAxis[PMDAxis1],PMDBreakpoint1, (0x2000<<16)
| 0x0000 );
PMDSetBreakpoint(&hAxis[PMDAxis1],PMDBreakpoint1,axis,PMDBreakpointNoAction,
PMDBreakpointActivityStatus );
/* ---- end ---- */
}

int main(int argc, char **argv)
{
    seed_open();
    setup_buffers(3);
    populate(3);
    initial_moves(3);
    wait_at_rest(3);
    int meant = argc > 1 && strcmp(argv[1], "meant") == 0;
    const char *mode = argc > 1 + meant ? argv[1 + meant] : "run";
    start_1_6();
    check(PMDUpdate(PMDAxis1), "PMDUpdate(PMDAxis1)");     /* the seed's call again: its result */
    if (meant)
        check(PMDUpdate(&hAxis[PMDAxis1]), "PMDUpdate");
    breakpoint_1_6();
    if (strcmp(mode, "poll") == 0) {
        PMDuint16 status;
        uint64_t start = 0, end = 0;
        unsigned long polls = 0;
        PMDFMU_GetHostTime(&hAxis[PMDAxis1], &start);
        do {
            check(PMDGetActivityStatus(&hAxis[PMDAxis1], &status), "PMDGetActivityStatus");
            polls++;
        } while (status & PMDActivityProfileSegmentMask);
        PMDFMU_GetHostTime(&hAxis[PMDAxis1], &end);
        printf("R poll %llu %llu %lu\n", (unsigned long long)start, (unsigned long long)end, polls);
    } else {
        run_cycles(5000);
    }
    {
        PMDAxis source = 9;
        PMDuint8 action = 9, trigger = 9;
        check(PMDGetBreakpoint(&hAxis[PMDAxis1], PMDBreakpoint1, &source, &action, &trigger), "PMDGetBreakpoint");
        printf("R breakpoint %u %u %u\n", source, action, trigger);
    }
    seed_close();
    return 0;
}
