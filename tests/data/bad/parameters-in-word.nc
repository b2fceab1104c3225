G21
G0 X#<depth>
