// For the harnesses: a valid EULUMDAT file (fuzz/corpus/photometry/sample_17.ldt, an
// ERCO downlight) written beside the input, so that a job naming b.ldt reaches every
// product path past the photometric reader.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz/fuzz_file.h"

namespace ilp::fuzz {

inline const char* const kValidLdt = R"ldt(﻿ERCO GmbH
1
1
1
0.0
91
1.0
ilumetrix_iku_rd19144_22000039-15_a_ip65a.ldt
Iku Surface-mounted downlight
B0000178_V01
"B000017800_01_L1_M1.ldt"
11.04.2025
128
0
200
76
0
0
0
0
0
100.00
100.00
1.00
0.00
1
-1
LED 4.8W neutral white
611.90
4000
82
6.90
0.47
0.57
0.64
0.74
0.78
0.83
0.88
0.90
0.92
0.93
0.00
0.00
1.00
2.00
3.00
4.00
5.00
6.00
7.00
8.00
9.00
10.00
11.00
12.00
13.00
14.00
15.00
16.00
17.00
18.00
19.00
20.00
21.00
22.00
23.00
24.00
25.00
26.00
27.00
28.00
29.00
30.00
31.00
32.00
33.00
34.00
35.00
36.00
37.00
38.00
39.00
40.00
41.00
42.00
43.00
44.00
45.00
46.00
47.00
48.00
49.00
50.00
51.00
52.00
53.00
54.00
55.00
56.00
57.00
58.00
59.00
60.00
61.00
62.00
63.00
64.00
65.00
66.00
67.00
68.00
69.00
70.00
71.00
72.00
73.00
74.00
75.00
76.00
77.00
78.00
79.00
80.00
81.00
82.00
83.00
84.00
85.00
86.00
87.00
88.00
89.00
90.00
762.34
764.07
764.24
765.62
766.66
767.87
769.77
768.91
770.29
770.12
769.60
767.35
763.72
760.09
755.59
749.54
743.14
734.84
725.68
712.71
696.81
680.55
666.03
649.95
633.70
615.37
598.08
575.08
551.91
529.09
508.86
485.86
461.66
435.72
411.17
388.86
364.31
342.01
320.05
297.05
273.53
254.00
234.46
217.17
200.05
182.93
166.33
152.33
137.80
124.84
111.18
100.11
88.53
76.94
65.88
54.64
44.09
33.02
23.52
15.73
9.86
5.53
3.46
2.42
1.73
1.38
1.38
1.21
1.04
1.04
0.86
0.86
0.69
0.69
0.69
0.52
0.52
0.52
0.35
0.35
0.35
0.35
0.17
0.17
0.17
0.17
0.17
0.17
0.00
0.00
0.00
)ldt";

// Writes kValidLdt as NAME in the work folder (once per process).
inline void write_valid_ldt(const std::string& name) {
  static bool written = false;
  if (written) return;
  std::ofstream(work_folder() / name, std::ios::binary) << kValidLdt;
  written = true;
}

}  // namespace ilp::fuzz
