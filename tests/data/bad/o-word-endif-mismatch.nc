G21
o5 if [1]
o6 endif
