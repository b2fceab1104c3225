(.../EAGLE/ulps/pcb-gcode/pcb-gcode.ulp)
(Copyright 2005 - 2012 by John Johnson)
(See readme.txt for licensing terms.)
(This file generated from the board:)
(.../projects/Handbrake/Handbrake.brd)
(Current profile is .../pcb-gcode-3.6.2.4/profiles/grbl-NuggetMill.pp  )
(This file generated 10/8/2021 11:25 PM)
(Settings from pcb-machine.h)
(spindle on time = 0.0000)
(spindle speed = 12000.0000)
(milling depth = -1.7000)
(tool change at 0.000000 0.000000 12.700000 )
(feed rate xy = F60    )
(feed rate z  = F100   )
(Z Axis Settings)
(  High     Up        Down     Drill)
(12.700000 	1.000000 	-0.050000 	-1.700000 )
(Settings from pcb-defaults.h)
(isolate min = 0.0254)
(isolate max = 0.1000)
(isolate step = 0.1000)
(Generated top outlines, top drill, )
(Unit of measure: mm)
(Metric Mode)
G21
(Absolute Coordinates)
G90
G0 Z12.700000 
G0 X0.000000 Y0.000000 
M3
G4 P0
G0 Z1.000000 
G0 X2.540000 Y2.540000 
G1 Z-0.425000 F100   
G1 X39.370000 Y2.540000 F60    
G1 X39.370000 Y27.940000 
G1 X2.540000 Y27.940000 
G1 X2.540000 Y2.540000 
G0 Z1.000000 
G1 Z-0.850000 F100   
G1 X39.370000 Y2.540000 F60    
G1 X39.370000 Y27.940000 
G1 X2.540000 Y27.940000 
G1 X2.540000 Y2.540000 
G0 Z1.000000 
G1 Z-1.275000 F100   
G1 X39.370000 Y2.540000 F60    
G1 X39.370000 Y27.940000 
G1 X2.540000 Y27.940000 
G1 X2.540000 Y2.540000 
G0 Z1.000000 
G1 Z-1.700000 F100   
G1 X39.370000 Y2.540000 F60    
G1 X39.370000 Y27.940000 
G1 X2.540000 Y27.940000 
G1 X2.540000 Y2.540000 
G0 Z12.700000 
M4
G0 X0 Y0
