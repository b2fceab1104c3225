G21 G90 F200
#1 = 3 #<depth> = -1.5 #<_safe> = 5
G0 X[#1*2] Y[#1 ** 2 - 1] Z#<_safe>
G1 Z#<depth> X[SIN[30]*10] Y[ATAN[1]/[2]]
#[#1+1] = [ABS[-4] MOD 3 + FIX[2.5] + FUP[0.1] + ROUND[1.5]]
G1 X##1 Y[SQRT[#4] + LN[EXP[1]]] Z[#<depth> / 2]
G1 X[[1 LT 2] AND [3 GE 3] OR [0 XOR 1]] Y[[1 EQ 1] + [2 NE 2] + [1 GT 0] + [1 LE 0]]
G0 X[EXISTS[#<depth>]] Y[COS[#5420]] Z[TAN[45] + ACOS[0] - ASIN[1]]
o<back> call [1] [2]
M2
o<back> sub
  o1 repeat [2]
    o2 if [#1 GT 0]
      G1 X#2
    o2 elseif [#1 LT 0]
      G1 Y#2
    o2 else
      o<back> return [1]
    o2 endif
  o1 endrepeat
  #<i> = 0
  o3 do
    #<i> = [#<i> + 1]
    o3 continue
  o3 while [#<i> LT 3]
  o4 while [1]
    o4 break
  o4 endwhile
o<back> endsub [#1]
