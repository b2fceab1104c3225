G0 X1.2.3
G1 X#1
o100 sub
G1 (unclosed
G0 A1
