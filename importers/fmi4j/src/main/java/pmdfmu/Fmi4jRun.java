/* SPDX-License-Identifier: BSD-2-Clause */
package pmdfmu;

import java.io.File;
import java.io.PrintWriter;

import no.ntnu.ihb.fmi4j.importer.fmi2.CoSimulationSlave;
import no.ntnu.ihb.fmi4j.importer.fmi2.Fmu;

/**
 * Runs the FMI 2.0 FMU with a script through FMI4j and writes one CSV row per
 * chip cycle: the cycle, then the Integer outputs named on the command line.
 *
 * Usage: Fmi4jRun FMU SCRIPT CYCLE_TIME CYCLES OUT.csv name=valueReference...
 * SCRIPT "-" sets no script: the FMU runs the profile it holds (pmdfmu pack), if any.
 */
public final class Fmi4jRun {
    public static void main(String[] args) throws Exception {
        String fmuPath = args[0], script = args[1], out = args[4];
        double cycleTime = Double.parseDouble(args[2]);
        int cycles = Integer.parseInt(args[3]);
        int n = args.length - 5;
        String[] names = new String[n];
        long[] vrs = new long[n + 1];
        for (int i = 0; i < n; i++) {
            String[] pair = args[5 + i].split("=");
            names[i] = pair[0];
            vrs[i + 1] = Long.parseLong(pair[1]);
        }
        vrs[0] = 10;                                  // chipTime
        int[] values = new int[n + 1];
        try (Fmu fmu = Fmu.from(new File(fmuPath));
             CoSimulationSlave slave = fmu.asCoSimulationFmu().newInstance();
             PrintWriter csv = new PrintWriter(out)) {
            check(slave.setupExperiment(0.0, 0.0, 0.0), "setupExperiment");
            check(slave.enterInitializationMode(), "enterInitializationMode");
            if (!script.equals("-"))
                check(slave.writeString(new long[] {4}, new String[] {script}).name().equals("OK"), "script");
            check(slave.exitInitializationMode(), "exitInitializationMode");
            csv.println("cycle," + String.join(",", names));
            for (int k = 0; k < cycles; k++) {
                check(slave.doStep(k * cycleTime, cycleTime), "doStep");
                slave.readInteger(vrs, values);
                StringBuilder row = new StringBuilder();
                for (int i = 0; i <= n; i++)
                    row.append(i == 0 ? "" : ",").append(values[i]);
                csv.println(row);
            }
            slave.terminate();
        }
    }

    private static void check(boolean ok, String what) {
        if (!ok)
            throw new IllegalStateException("FMI4j: " + what + " failed");
    }
}
