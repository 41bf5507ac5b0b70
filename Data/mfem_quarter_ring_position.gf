FiniteElementSpace
FiniteElementCollection: NURBS2
VDim: 3
Ordering: 0

1
0
0
2
1
0
0
2
1
2
1
2
0
1
2
0
0
1
2
0
1
2
1
2
0
0
0
0
1
1
1
1
0
0
1
1
