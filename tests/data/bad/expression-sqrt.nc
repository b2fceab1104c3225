G21
#1 = 2
G0 X[SQRT[-#1]]
