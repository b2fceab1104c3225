/G0 X1 (block delete)
g1 x 2 y - 3 f 100 ; lower case and blanks
G17 G2 X4 Y-1 I1 J0 *45
G18 G3 X5 Z1 I.5 K0
G19 G2 Y0 Z0 J-1 K0
M30
