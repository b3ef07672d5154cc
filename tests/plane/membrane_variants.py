#!/usr/bin/env python3
"""Measurement behind the choice of the 4-node membrane (CPS4, the S4 membrane):
QM6 with Taylor's correction (what superjoin has) against the Pian-Sumihara
5-beta hybrid-stress element, on the MacNeal-Harder straight cantilever (6 x 1,
regular / trapezoidal / parallelogram, in-plane shear, reference 0.1081) and
curved beam (in-plane shear, reference 0.08734). Independent Python
implementations of both elements (no numpy), 2 x 2 Gauss points.

usage: python3 tests/plane/membrane_variants.py

Result (normalised tip deflection):
  QM6 [0.9929, 0.0515, 0.6323] curved 0.8875
  PS  [0.9929, 0.0516, 0.6323] curved 0.8875
The QM6 column reproduces superjoin's CPS4 (tests/plane/verify_plane.py).
"""
import math
# small dense linear algebra
def matmul(A,B): return [[sum(A[i][k]*B[k][j] for k in range(len(B))) for j in range(len(B[0]))] for i in range(len(A))]
def T(A): return [list(r) for r in zip(*A)]
def solve(A,b):
    n=len(A); M=[A[i][:]+[b[i]] for i in range(n)]
    for c in range(n):
        p=max(range(c,n),key=lambda r:abs(M[r][c])); M[c],M[p]=M[p],M[c]
        for r in range(c+1,n):
            f=M[r][c]/M[c][c]
            if f: 
                for k in range(c,n+1): M[r][k]-=f*M[c][k]
    x=[0]*n
    for r in range(n-1,-1,-1): x[r]=(M[r][n]-sum(M[r][k]*x[k] for k in range(r+1,n)))/M[r][r]
    return x
def inv(A):
    n=len(A); cols=[solve(A,[1.0 if i==j else 0.0 for i in range(n)]) for j in range(n)]
    return T(cols)
XI=[-1,1,1,-1]; ET=[-1,-1,1,1]
G=1/math.sqrt(3); GP=[(-G,-G),(G,-G),(G,G),(-G,G)]
def D(E,nu):
    c=E/(1-nu*nu); return [[c,c*nu,0],[c*nu,c,0],[0,0,c*(1-nu)/2]]
def jac(x,xi,eta):
    dn=[[XI[i]*(1+eta*ET[i])/4 for i in range(4)],[ET[i]*(1+xi*XI[i])/4 for i in range(4)]]
    J=[[sum(dn[a][i]*x[i][b] for i in range(4)) for b in range(2)] for a in range(2)]
    return J,dn
def det(J): return J[0][0]*J[1][1]-J[0][1]*J[1][0]
def bmat(x,xi,eta):
    J,dn=jac(x,xi,eta); d=det(J)
    Ji=[[J[1][1]/d,-J[0][1]/d],[-J[1][0]/d,J[0][0]/d]]
    dxy=[[Ji[a][0]*dn[0][i]+Ji[a][1]*dn[1][i] for i in range(4)] for a in range(2)]
    B=[[0]*8 for _ in range(3)]
    for i in range(4):
        B[0][2*i]=dxy[0][i]; B[1][2*i+1]=dxy[1][i]; B[2][2*i]=dxy[1][i]; B[2][2*i+1]=dxy[0][i]
    return B,d
def qm6(x,Dm,t):
    J0,_=jac(x,0,0); d0=det(J0)
    kuu=[[0]*8 for _ in range(8)]; kua=[[0]*4 for _ in range(8)]; kaa=[[0]*4 for _ in range(4)]
    for xi,eta in GP:
        B,d=bmat(x,xi,eta)
        dp=[[-2*xi,0],[0,-2*eta]]  # columns: mode1 d/dxi,d/deta ; mode2
        adj=[[J0[1][1],-J0[0][1]],[-J0[1][0],J0[0][0]]]
        pxy=[[ (adj[a][0]*dp[0][m]+adj[a][1]*dp[1][m])/d for m in range(2)] for a in range(2)]
        Ba=[[0]*4 for _ in range(3)]
        for m in range(2):
            Ba[0][m]=pxy[0][m]; Ba[2][m]=pxy[1][m]; Ba[1][2+m]=pxy[1][m]; Ba[2][2+m]=pxy[0][m]
        DB=matmul(Dm,B); DA=matmul(Dm,Ba)
        for i in range(8):
            for j in range(8): kuu[i][j]+=t*d*sum(B[k][i]*DB[k][j] for k in range(3))
            for j in range(4): kua[i][j]+=t*d*sum(B[k][i]*DA[k][j] for k in range(3))
        for i in range(4):
            for j in range(4): kaa[i][j]+=t*d*sum(Ba[k][i]*DA[k][j] for k in range(3))
    X=matmul(inv(kaa),T(kua))
    return [[kuu[i][j]-sum(kua[i][k]*X[k][j] for k in range(4)) for j in range(8)] for i in range(8)]
def ps(x,Dm,t):
    # Pian-Sumihara 5-beta
    a1=sum(XI[i]*x[i][0] for i in range(4))/4; a3=sum(ET[i]*x[i][0] for i in range(4))/4
    b1=sum(XI[i]*x[i][1] for i in range(4))/4; b3=sum(ET[i]*x[i][1] for i in range(4))/4
    C=inv(Dm)
    H=[[0]*5 for _ in range(5)]; Gm=[[0]*8 for _ in range(5)]
    for xi,eta in GP:
        B,d=bmat(x,xi,eta)
        P=[[1,0,0,a1*a1*eta,a3*a3*xi],[0,1,0,b1*b1*eta,b3*b3*xi],[0,0,1,a1*b1*eta,a3*b3*xi]]
        CP=matmul(C,P)
        for i in range(5):
            for j in range(5): H[i][j]+=t*d*sum(P[k][i]*CP[k][j] for k in range(3))
            for j in range(8): Gm[i][j]+=t*d*sum(P[k][i]*B[k][j] for k in range(3))
    X=matmul(inv(H),Gm)
    return matmul(T(Gm),X)
def cantilever(elem, nodes, quads, fixed, loads, Dm, t):
    n=2*len(nodes); K=[[0.0]*n for _ in range(n)]
    for q in quads:
        ke=elem([nodes[i] for i in q],Dm,t)
        dofs=[2*i+k for i in q for k in range(2)]
        for a,da in enumerate(dofs):
            for b,db in enumerate(dofs): K[da][db]+=ke[a][b]
    free=[i for i in range(n) if i not in fixed]
    f=[loads.get(i,0.0) for i in free]
    u=solve([[K[i][j] for j in free] for i in free],f)
    full=[0.0]*n
    for i,v in zip(free,u): full[i]=v
    return full
def mh(shape, elem):
    xb=[float(i) for i in range(7)]; xt=list(xb)
    if shape=="trap":
        d=[0,.2,-.2,.2,-.2,.2,0]; xb=[x-di/2 for x,di in zip(xb,d)]; xt=[x+di/2 for x,di in zip(xt,d)]
    elif shape=="para":
        xb=[x-(.1 if 0<i<6 else 0) for i,x in enumerate(xb)]; xt=[x+(.1 if 0<i<6 else 0) for i,x in enumerate(xt)]
    nodes=[]
    for i in range(7): nodes+= [(xb[i],0.0),(xt[i],0.2)]
    quads=[(2*i,2*i+2,2*i+3,2*i+1) for i in range(6)]
    u=cantilever(elem,nodes,quads,{0,1,2,3},{2*12+1:0.5,2*13+1:0.5},D(1e7,.3),.1)
    return (u[2*12+1]+u[2*13+1])/2/0.1081
def curved(elem):
    nodes=[]
    for i in range(7):
        a=math.pi/2*i/6
        nodes+=[(4.12*math.cos(a),4.12*math.sin(a)),(4.32*math.cos(a),4.32*math.sin(a))]
    quads=[(2*i,2*i+1,2*i+3,2*i+2) for i in range(6)]   # counter-clockwise: outward, then along the arc
    u=cantilever(elem,nodes,quads,{0,1,2,3},{2*12+1:0.5,2*13+1:0.5},D(1e7,.25),.1)
    return (u[2*12+1]+u[2*13+1])/2/0.08734
for name,el in (("QM6",qm6),("PS",ps)):
    print(name, [round(mh(s,el),4) for s in ("reg","trap","para")], round(curved(el),4))
