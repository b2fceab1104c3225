G21
  o<drill> call [1] [2]
