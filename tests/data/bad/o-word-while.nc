G21
o102 while [1]
o102 endwhile
