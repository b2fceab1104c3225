G21
o100 sub
G0 X1
o100 endsub
