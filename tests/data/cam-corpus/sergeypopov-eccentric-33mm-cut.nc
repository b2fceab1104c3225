(Exported by FreeCAD)
(Post Processor: grbl_post)
(Output Time:2023-08-13 14:12:27.613665)
(Begin preamble)
G17 G90
G21
(Block-name: G54)
(Block-expand: 0)
(Block-enable: 1)
(Begin operation: G54)
(Path: G54)
G54
G0 Z5.000
(Finish operation: G54)
(Block-name: 33mm Endmill003)
(Block-expand: 0)
(Block-enable: 1)
(Begin operation: 33mm Endmill003)
(Path: 33mm Endmill003)
(33mm Endmill003)
(Begin toolchange)
( M6 T2 )
(Finish operation: 33mm Endmill003)
(Block-name: Profile+1)
(Block-expand: 0)
(Block-enable: 1)
(Begin operation: Profile+1)
(Path: Profile+1)
(Profile+1)
(Compensated Tool Path. Diameter: 33.0)
G0 Z5.000
G0 X16.456 Y16.452
G0 Z3.000
G1 X16.456 Y16.452 Z-11.000 F100.000
G2 X23.273 Y0.243 Z-11.000 I-16.459 J-16.460 K0.000 F200.000
G1 X23.250 Y-0.903 Z-11.000 F200.000
G2 X-23.272 Y0.582 Z-11.000 I-23.256 J0.909 K0.000 F200.000
G2 X16.456 Y16.452 Z-11.000 I23.269 J-0.589 K0.000 F200.000
(Finish operation: Profile+1)
(Block-name: Profile_0)
(Block-expand: 0)
(Block-enable: 1)
(Begin operation: Profile_0)
(Path: Profile_0)
(Profile_0)
(Compensated Tool Path. Diameter: 33.0)
G1 X16.315 Y16.311 Z-11.000 F100.000
G2 X23.073 Y0.253 Z-11.000 I-16.317 J-16.318 K0.000 F200.000
G1 X23.051 Y-0.893 Z-11.000 F200.000
G2 X-23.072 Y0.574 Z-11.000 I-23.056 J0.898 K0.000 F200.000
G2 X16.315 Y16.311 Z-11.000 I23.069 J-0.581 K0.000 F200.000
(Finish operation: Profile_0)
(Block-name: Profile-1)
(Block-expand: 0)
(Block-enable: 1)
(Begin operation: Profile-1)
(Path: Profile-1)
(Profile-1)
(Compensated Tool Path. Diameter: 33.0)
G1 X15.533 Y15.533 Z-11.000 F100.000
G2 X21.912 Y1.556 Z-11.000 I-15.538 J-15.536 K0.000 F200.000
G2 X19.201 Y-10.674 Z-11.000 I-21.756 J-1.593 K0.000 F200.000
G2 X-21.949 Y-1.118 Z-11.000 I-19.205 J10.680 K0.000 F200.000
G2 X15.533 Y15.533 Z-11.000 I21.944 J1.116 K0.000 F200.000
(Finish operation: Profile-1)
(Block-name: Profile-2)
(Block-expand: 0)
(Block-enable: 1)
(Begin operation: Profile-2)
(Path: Profile-2)
(Profile-2)
(Compensated Tool Path. Diameter: 33.0)
G1 X14.825 Y14.827 Z-11.000 F100.000
G2 X20.954 Y-0.780 Z-11.000 I-14.831 J-14.831 K0.000 F200.000
G1 X20.916 Y-1.484 Z-11.000 F200.000
G2 X-20.946 Y1.183 Z-11.000 I-20.921 J1.491 K0.000 F200.000
G2 X14.825 Y14.827 Z-11.000 I20.940 J-1.187 K0.000 F200.000
(Finish operation: Profile-2)
(Block-name: Profile-3)
(Block-expand: 0)
(Block-enable: 1)
(Begin operation: Profile-3)
(Path: Profile-3)
(Profile-3)
(Compensated Tool Path. Diameter: 33.0)
G1 X14.118 Y14.120 Z-11.000 F100.000
G2 X19.955 Y-0.726 Z-11.000 I-14.124 J-14.124 K0.000 F200.000
G1 X19.917 Y-1.430 Z-11.000 F200.000
G2 X-19.947 Y1.144 Z-11.000 I-19.923 J1.437 K0.000 F200.000
G2 X14.118 Y14.120 Z-11.000 I19.941 J-1.148 K0.000 F200.000
(Finish operation: Profile-3)
(Block-name: Profile-4)
(Block-expand: 0)
(Block-enable: 1)
(Begin operation: Profile-4)
(Path: Profile-4)
(Profile-4)
(Compensated Tool Path. Diameter: 33.0)
G1 X13.411 Y13.413 Z-11.000 F100.000
G2 X18.957 Y-0.673 Z-11.000 I-13.417 J-13.417 K0.000 F200.000
G1 X18.919 Y-1.377 Z-11.000 F200.000
G2 X-18.948 Y1.105 Z-11.000 I-18.924 J1.384 K0.000 F200.000
G2 X13.411 Y13.413 Z-11.000 I18.942 J-1.109 K0.000 F200.000
(Finish operation: Profile-4)
(Block-name: Profile-5)
(Block-expand: 0)
(Block-enable: 1)
(Begin operation: Profile-5)
(Path: Profile-5)
(Profile-5)
(Compensated Tool Path. Diameter: 33.0)
G1 X12.704 Y12.706 Z-11.000 F100.000
G2 X17.958 Y-0.619 Z-11.000 I-12.710 J-12.710 K0.000 F200.000
G1 X17.920 Y-1.323 Z-11.000 F200.000
G2 X-17.949 Y1.066 Z-11.000 I-17.925 J1.330 K0.000 F200.000
G2 X12.704 Y12.706 Z-11.000 I17.943 J-1.070 K0.000 F200.000
(Finish operation: Profile-5)
(Block-name: Profile-6)
(Block-expand: 0)
(Block-enable: 1)
(Begin operation: Profile-6)
(Path: Profile-6)
(Profile-6)
(Compensated Tool Path. Diameter: 33.0)
G1 X11.997 Y11.999 Z-11.000 F100.000
G2 X16.960 Y-0.565 Z-11.000 I-12.003 J-12.003 K0.000 F200.000
G1 X16.922 Y-1.269 Z-11.000 F200.000
G2 X-16.949 Y1.027 Z-11.000 I-16.927 J1.276 K0.000 F200.000
G2 X11.997 Y11.999 Z-11.000 I16.943 J-1.031 K0.000 F200.000
(Finish operation: Profile-6)
(Block-name: post_amble)
(Block-expand: 0)
(Block-enable: 1)
(Begin postamble)
M5
G17 G90
M2
