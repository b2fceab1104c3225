G21
G0 X1 (rapid to start
G1 X2
