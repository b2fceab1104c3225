G21
o<a> sub
o<a> call
o<a> endsub
o<a> call
