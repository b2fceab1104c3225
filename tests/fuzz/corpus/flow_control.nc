G21 G90 G17 G94 F300
G0 X0 Y0 Z0
o<s0> sub
  #<t> = [[[#2 / [ABS[0.699] + 1]] GT [-5.647 + #1]] AND [#3 NE 0]]
  G0 X[#2 MOD 80 - 40] Y[3.068 MOD 80 - 40]
  o100 if [#1 GT 0]
    o<s0> return [#1 + #<t>]
  o100 endif
  G0 X[[[[#1 LE #<t>] OR [#2 NE 0]] MOD 7] MOD 80 - 40] Y[[[#<t> / [ABS[-1.420] + 1]] * #1] MOD 80 - 40]
  G1 X[#3 MOD 80 - 40] Z[2.233 MOD 80 - 40]
  G1 X[[-0.554 + SQRT[ABS[#1]]] MOD 80 - 40] Y[[1.334 - [[-0.152 LE 7.504] AND [-6.659 NE 0]]] MOD 80 - 40] Z[[[SQRT[ABS[-8.101]] LE -1.547] AND [#2 NE 0]] MOD 80 - 40]
o<s0> endsub [#2]
#<_d102> = 0
o101 do
  #<_d102> = [#<_d102> + 1]
  G0 X[6.896 MOD 80 - 40] Y[-6.493 MOD 80 - 40]
  G1 X[ATAN[FUP[2.481]]/[-2.497] MOD 80 - 40]
o101 while [#<_d102> LT 2]
o102 if [[[7.953 GT 8.091] AND [-0.034 NE 0]] LE [#<_d102> / [ABS[7.126] + 1]]]
  G0 X[ATAN[[0.487 / [ABS[#<_d102>] + 1]]]/[-8.948] MOD 80 - 40] Z[SQRT[ABS[[[#<_d102> LE 5.970] AND [#<_d102> NE 0]]]] MOD 80 - 40]
  G0 X[[[#<_d102> LE [-8.113 / [ABS[#<_d102>] + 1]]] AND [-0.642 NE 0]] MOD 80 - 40] Y[-8.490 MOD 80 - 40] Z[-3.803 MOD 80 - 40] #33 = [[-2.379 LE 1.544] AND [#<_d102> NE 0]]
  G0 X[[[6.544 - #33] MOD 3] MOD 80 - 40] Y[SIN[ATAN[-6.240]/[-6.544]] MOD 80 - 40] Z[[[8.411 GT 2.778] OR [-4.937 NE 0]] MOD 80 - 40]
o102 elseif [#<_d102> LT -6.262]
  o103 if [-7.740 LT [[#<_d102> LE 2.159] AND [4.337 NE 0]]]
    o<s0> call [ATAN[SQRT[ABS[#<_d102>]]]/[-3.287]] [ATAN[SQRT[ABS[#<_d102>]]]/[-2.157]] [[[5.486 / [ABS[-2.584] + 1]] / [ABS[[[-7.282 LE -2.338] AND [#<_d102> NE 0]]] + 1]]]
    G1 X[#<_value> MOD 80 - 40]
  o103 endif
o102 endif
o104 repeat [1]
  o105 if [[3.367 / [ABS[#33] + 1]] GE 4.231]
    G0 X[[[SIN[#33] GT [[5.550 LE 1.878] AND [7.674 NE 0]]] AND [7.654 NE 0]] MOD 80 - 40] Y[#<_d102> MOD 80 - 40] #31 = SQRT[ABS[#33]]
    G1 X[-5.828 MOD 80 - 40] Y[SQRT[ABS[#31]] MOD 80 - 40] #35 = ROUND[#31]
    G0 X[8.383 MOD 80 - 40] Y[SQRT[ABS[COS[#31]]] MOD 80 - 40]
  o105 elseif [SQRT[ABS[5.183]] GE [[#35 GT #35] AND [#<_d102> NE 0]]]
    #31 = ROUND[-1.811]
  o105 else
    o<s0> call [FIX[[-5.229 - #<_d102>]]] [FUP[ATAN[#31]/[-3.860]]] [[[#31 / [ABS[#35] + 1]] / [ABS[-8.344] + 1]]]
    G1 X[#<_value> MOD 80 - 40]
  o105 endif
o104 endrepeat
o106 if [SIN[#33] EQ [-1.605 / [ABS[-2.523] + 1]]]
  #<_i108> = 0
  o107 while [#<_i108> LT 1]
    #<_i108> = [#<_i108> + 1]
    #<_d109> = 0
    o108 do
      #<_d109> = [#<_d109> + 1]
      G1 X[-5.042 MOD 80 - 40] Y[[[[#31 LE -3.622] AND [#35 NE 0]] MOD 9] MOD 80 - 40] Z[ATAN[-1.011]/[4.197] MOD 80 - 40] #33 = 5.612
    o108 while [#<_d109> LT 2]
  o107 endwhile
o106 elseif [[[2.886 * #33] NE [-8.200 / [ABS[-7.567] + 1]]] XOR [#35 GT 0]]
  o109 if [[-5.064 * 0.725] LE SQRT[ABS[1.665]]]
    G1 X[[[2.100 + #33] / [ABS[0.098] + 1]] MOD 80 - 40] Y[[SQRT[ABS[-5.396]] * 0.285] MOD 80 - 40] #34 = SQRT[ABS[4.528]]
    G1 X[7.183 MOD 80 - 40] Y[-3.161 MOD 80 - 40]
  o109 endif
o106 endif
G0 X[[[3.678 / [ABS[#31] + 1]] * 2.723] MOD 80 - 40] Y[[SQRT[ABS[5.089]] / [ABS[[[#33 GT 2.381] AND [#31 NE 0]]] + 1]] MOD 80 - 40]
G1 X[FIX[[[#35 LE #31] OR [#35 NE 0]]] MOD 80 - 40]
G0 X[#31 MOD 80 - 40] Z[FUP[[#35 / [ABS[#33] + 1]]] MOD 80 - 40] #35 = COS[#31]
o<s0> call
G1 X[#<_value> MOD 80 - 40]
G0 X[[[SQRT[ABS[1.682]] GT SQRT[ABS[5.375]]] OR [-7.975 NE 0]] MOD 80 - 40] Z[SQRT[ABS[[#31 / [ABS[#31] + 1]]]] MOD 80 - 40]
#<_d111> = 0
o110 do
  #<_d111> = [#<_d111> + 1]
  o<s0> call
o110 while [#<_d111> LT 1]
M2
