(.../pcb-gcode-3.6.2.4/pcb-gcode.ulp)
(Copyright 2005 - 2012 by John Johnson)
(See readme.txt for licensing terms.)
(This file generated from the board:)
(.../atmega_midi_pg800/eagle/atmega_midi_pg800.brd)
(Current profile is .../pcb-gcode-3.6.2.4/profiles/mach.pp  )
(This file generated 11/18/16 11:04 PM)
(Settings from pcb-machine.h)
(spindle on time = 0.0000)
(spindle speed = 15000.0000)
(milling depth = -0.0730)
(tool change at 0.0000  0.0000  1.5000  )
(feed rate xy = F10    )
(feed rate z  = F5     )
(Z Axis Settings)
(  High     Up        Down     Drill)
(0.2500  	0.0500  	-0.0035 	-0.0710 )
(Settings from pcb-defaults.h)
(isolate min = 0.0040)
(isolate max = 0.0200)
(isolate step = 0.0025)
(Generated bottom outlines, bottom drill, )
(Unit of measure: inch)
(Inch Mode)
G20
(Absolute Coordinates)
G90
S15000
G00 Z0.2500  
G00 X0.0000  Y0.0000  
M03
G04 P0.000000
G00 Z0.0500  
G00 X0.0300  Y0.0300  
G01 Z-0.0730 F5     
G01 X0.0300  Y3.1100  F10    
G01 X-0.0200 Y3.1500  
G01 X-3.9300 Y3.1500  
G01 X-3.9800 Y3.1100  
G01 X-3.9800 Y0.0300  
G01 X-3.9000 Y-0.0300 
G01 X-0.0500 Y-0.0300 
G00 Z0.0500  
G00 X-0.0400 Y-0.0300 
G01 Z-0.0730 F5     
G01 X0.0300  Y0.0300  F10    
G00 Z0.0500  
G00 X-1.9300 Y0.1100  
G01 Z-0.0730 F5     
G01 X-1.9800 Y0.1100  F10    
G01 X-1.9800 Y0.1600  
G01 X-1.9500 Y0.1600  
G00 Z0.0500  
G00 X-1.9300 Y0.1600  
G01 Z-0.0730 F5     
G01 X-1.9300 Y0.1100  F10    
G00 Z0.0500  
G00 X-1.0700 Y1.7100  
G01 Z-0.0730 F5     
G01 X-1.0700 Y1.7600  F10    
G01 X-1.0400 Y1.7600  
G00 Z0.0500  
G00 X-1.0200 Y1.7600  
G01 Z-0.0730 F5     
G01 X-1.0200 Y1.7100  F10    
G01 X-1.0700 Y1.7100  
G00 Z0.0500  
G00 X-3.4600 Y1.5900  
G01 Z-0.0730 F5     
G01 X-3.4600 Y1.5400  F10    
G01 X-3.5100 Y1.5400  
G01 X-3.5100 Y1.5900  
G01 X-3.4800 Y1.5900  
G00 Z0.2500  
M05
M02
